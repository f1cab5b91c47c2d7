"""The target concrete: the HJC parameter set of a scene or a shot, built in one place for every level.

The cavity level, the finite-element level and the levels of users' shots (``levels``, the command line) take
their target's HJC set (``hjc.HJC``) from here, composed in this order:

1. the paper's Table 1 (``table1``), read from the reference values by id (``refs["table1.fc"].si``, SI) through
   ``hjc.TABLE1_FIELDS``;
2. the conventions of the configuration's ``concrete`` section (``configured``): the lock strain, the tension
   branch and the rate floor (``CONVENTIONS``; ``hjc`` states each);
3. a scene's material switches (``material_switches``): a material effect of ``hjc_effects.MATERIAL_EFFECTS``
   the scene leaves out is switched off, a lock or tension convention it names replaces the configured one;
   a study's HJC fields and a calibrated ``strength_scale`` are set with them;
4. for a user's shot, the scaling to its concrete strength and density (``hjc_for_strength``) and the level's
   DO1 calibration (``shot_concrete``).

Concrete of any strength (``hjc_for_strength``): the Table 1 set (fc = 48 MPa) scaled to the shot's fc by material
data, each quantity as a ratio to its value at 48 MPa so that the Table 1 set is returned exactly at 48 MPa:

- the normalised strength surface (A, B, N, C, SFMAX) is kept: HJC normalises stresses and pressures by fc, and
  the triaxial criteria with an fc dependence move its normalised meridian by about 5 % between 30 and 100 MPa
  (the Ottosen criterion of CEB-FIP MC90 / EN 1992-2 Annex LL; Attard & Setunge 1996 within its tests), as the
  shape-invariant scaling of the K&C model does (docs/levels.md, workflow/data/hjc_sets.csv);
- the crush point as Holmquist, Johnson & Cook (1993) determine it: pc = fc/3 (the pressure of the uniaxial
  compression test at failure), mu_c = pc/K with K the elastic bulk modulus;
- the elastic moduli as Eci in the fib Model Code 2010 (Eq 5.1-21: E proportional to fcm^(1/3)), Poisson's ratio
  kept;
- the tensile strength as fctm in the fib Model Code 2010 (Eqs 5.1-3a/b: 0.30 fck^(2/3) up to fck = 50 MPa,
  2.12 ln(1 + fcm/10) above; fck = fcm - 8 MPa, Eq 5.1-1), the shot's fc taken as the mean strength fcm.

Carried over unchanged: the damage constants (eps0, D1, D2, EFMIN), the compaction of the fully dense material
(pl, mu_l, K1-K3) and the conventions of the configuration. The density is the shot's.

No file is read here: the reference values and the config section come in loaded.
"""
from __future__ import annotations

import dataclasses
import math

from ..errors import ParameterError
from ..units import MPA
from .effects import MATERIAL_EFFECTS
from .hjc import HJC, LOCKS, TENSIONS, from_table1

# the configuration's conventions (the ``concrete`` section) and what each admits
CONVENTIONS = ("lock", "tension", "rate_floor")
ALLOWED = {"lock": f"one of {list(LOCKS)}", "tension": f"one of {list(TENSIONS)}", "rate_floor": "true or false"}
# fc range of the HJC scaling rule (Pa): the design-code relations it uses are stated for normal- and
# high-strength concrete; outside it the rule is an extrapolation the cavity and fe levels refuse
FC_RULE_RANGE = (20e6, 200e6)
HJC_SCALING_RULE = {
    "name": "HJC set of Table 1 scaled with fc by material data",
    "scaled": {
        "pc": "pc = fc/3 (Holmquist, Johnson & Cook 1993: the pressure of the uniaxial compression test at failure)",
        "muc": "muc = pc/K, K scaled as E (Holmquist, Johnson & Cook 1993)",
        "G": "G and K proportional to Eci = Ec0 (fcm/10)^(1/3) at a fixed Poisson's ratio (fib Model Code 2010, "
             "Eq 5.1-21)",
        "T": "T proportional to fctm: 0.30 fck^(2/3) MPa up to fck = 50 MPa, 2.12 ln(1 + fcm/10) MPa above, "
             "fck = fcm - 8 MPa (fib Model Code 2010, Eqs 5.1-3a/b and 5.1-1), fcm = the shot's fc",
        "fc": "the shot's compressive strength",
        "rho0": "the shot's density",
    },
    "carried_over": ["A", "B", "N", "C", "eps0", "smax", "D1", "D2", "efmin", "pl", "mul", "k1", "k2", "k3",
                     "lock", "tension", "rate_floor"],
    "kept_normalised_because": "the fc dependence of the normalised triaxial meridian is about 5 % between 30 and "
                               "100 MPa in the criteria of workflow/data/hjc_sets.csv (docs/levels.md)",
    "exact_at": "fc = 48 MPa (Table 1): every scaled quantity is its Table 1 value times a ratio equal to 1",
    "range_pa": list(FC_RULE_RANGE),
}


def elastic_modulus_mc2010(fcm):
    """Eci of the fib Model Code 2010 (Eq 5.1-21, quartzite aggregate, Ec0 = 21.5 GPa) at mean strength fcm (Pa)."""
    return 21.5e9 * (fcm / 10e6) ** (1.0 / 3.0)


def tensile_strength_mc2010(fcm):
    """fctm of the fib Model Code 2010 (Eqs 5.1-3a/b) at mean strength fcm (Pa), with fck = fcm - 8 MPa (Eq 5.1-1)."""
    fck = fcm / MPA - 8.0
    return MPA * (0.30 * fck ** (2.0 / 3.0) if fck <= 50.0 else 2.12 * math.log(1.0 + 0.1 * fcm / MPA))


HJC_FIELDS = tuple(f.name for f in dataclasses.fields(HJC))


def table1(refs, **fields) -> HJC:
    """HJC of the paper's Table 1 (reference values by id, ``refs["table1.QUANTITY"].si``), with ``fields`` set."""
    unknown = sorted(set(fields) - set(HJC_FIELDS))
    if unknown:
        raise ParameterError("concrete", unknown[0], fields[unknown[0]], f"an HJC field: one of {list(HJC_FIELDS)}")
    return from_table1(lambda quantity: refs[f"table1.{quantity}"].si, **fields)


def conventions(cfg) -> dict:
    """The conventions of the ``concrete`` config section (lock, tension, rate_floor), each checked."""
    unknown = sorted(set(cfg) - set(CONVENTIONS))
    if unknown:
        raise ParameterError("concrete", unknown[0], cfg[unknown[0]], f"a convention: one of {list(CONVENTIONS)}")
    for key in CONVENTIONS:
        if key not in cfg:
            raise ParameterError("concrete", key, None, f"required: {ALLOWED[key]}")
    if cfg["lock"] not in LOCKS:
        raise ParameterError("concrete", "lock", cfg["lock"], ALLOWED["lock"])
    if cfg["tension"] not in TENSIONS:
        raise ParameterError("concrete", "tension", cfg["tension"], ALLOWED["tension"])
    if not isinstance(cfg["rate_floor"], bool):
        raise ParameterError("concrete", "rate_floor", cfg["rate_floor"], ALLOWED["rate_floor"])
    return {key: cfg[key] for key in CONVENTIONS}


def configured(refs, cfg, **fields) -> HJC:
    """Table 1 HJC with the conventions of the ``concrete`` config section ``cfg``; ``fields`` set any other field
    (a scene's material switches, a study's variant, a calibrated strength_scale)."""
    return table1(refs, **{**conventions(cfg), **fields})


def material_switches(effects, named, cfg) -> dict:
    """HJC fields a scene changes from the configured concrete.

    ``effects``: the scene's effect names (the material effects it leaves
    out are switched off, ``hjc_effects.MATERIAL_EFFECTS``); ``named``: the
    conventions the scene names (lock, tension); ``cfg``: the ``concrete``
    config section. Empty when the scene needs nothing but the configured
    concrete.
    """
    configured_conventions = conventions(cfg)
    for key, value in named.items():
        if key not in CONVENTIONS:
            raise ParameterError("scene", key, value, f"a convention of the concrete: one of {list(CONVENTIONS)}")
    listed = set(effects)
    over = {}
    for name, off in MATERIAL_EFFECTS.items():
        if name not in listed:
            over.update(off)
    over.update({k: v for k, v in named.items() if v != configured_conventions[k]})
    return over


def hjc_for_strength(fc, base: HJC, density=None) -> HJC:
    """The HJC set ``base`` (Table 1) scaled to compressive strength fc (Pa) by HJC_SCALING_RULE."""
    lo, hi = FC_RULE_RANGE
    if not (math.isfinite(fc) and lo <= fc <= hi):
        raise ParameterError("shot", "fc_MPa", fc / MPA, f"{lo / MPA:g} <= fc_MPa <= {hi / MPA:g} at the cavity and fe "
                             "levels: the range of the HJC scaling rule")
    r = fc / base.fc
    e = elastic_modulus_mc2010(fc) / elastic_modulus_mc2010(base.fc)
    t = tensile_strength_mc2010(fc) / tensile_strength_mc2010(base.fc)
    return dataclasses.replace(base, fc=fc, pc=base.pc * r, muc=base.muc * r / e, G=base.G * e, T=base.T * t,
                               rho0=base.rho0 if density is None else density)


def shot_concrete(base: HJC, fc, density=None, strength_scale=None) -> HJC:
    """The concrete of a user's shot: ``base`` scaled to its fc and density (hjc_for_strength), with the level's
    DO1 calibration, the strength scale of the cavity level, when one is given."""
    scaled = hjc_for_strength(fc, base, density)
    return scaled if strength_scale is None else dataclasses.replace(scaled, strength_scale=strength_scale)
