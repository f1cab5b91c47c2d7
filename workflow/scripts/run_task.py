"""Run the task of the calling Snakemake rule (the function of the rule's name in its task module).

Output goes both to the terminal and to the rule's log file; numba's parallel kernels get the rule's threads. The
job ends when its Snakemake ends, even when Snakemake was killed (pipeline.end_with_parent): an orphaned job never
writes its outputs later.
"""
import contextlib
import os
import sys

# the job's parallel kernels use the threads Snakemake gave it, no more (numba reads this when first imported)
os.environ["NUMBA_NUM_THREADS"] = str(snakemake.threads)  # noqa: F821

from penetration.pipeline.dispatch import end_with_parent, run

end_with_parent()


class Tee:
    def __init__(self, *streams):
        self.streams = streams

    def write(self, text):
        for s in self.streams:
            s.write(text)

    def flush(self):
        for s in self.streams:
            s.flush()


with open(snakemake.log[0], "w") as log:  # noqa: F821
    with contextlib.redirect_stdout(Tee(sys.stdout, log)), contextlib.redirect_stderr(Tee(sys.stderr, log)):
        run(snakemake.rule, snakemake.input.task, snakemake.input, snakemake.output, snakemake.params)  # noqa: F821
