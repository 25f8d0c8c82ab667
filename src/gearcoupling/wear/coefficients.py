"""Dimensional wear coefficients ``k`` (mm³ per N·m of normal force times sliding distance,
each flank) of the usual lubrication regimes, with where each number comes from.

Archard's law in dimensional form: a flank loses the volume ``V = k W s`` (``W`` the normal
force, ``s`` the sliding distance), locally the depth ``dh = k p ds``. Published
coefficients are mostly dimensionless, ``K = k H`` with ``H`` the hardness of the softer
surface; they are converted here with :data:`HARDNESS_MPA`, the hardness of the spec's
default material (a ~300 HB quenched-and-tempered steel, ``gearcoupling.spec``).
Every regime is a range: wear coefficients scatter over a decade or more between tests of
nominally equal pairs (Rabinowicz, "The Wear Coefficient — Magnitude, Scatter, Uses",
J. Lubr. Technol. 103(2):188, 1981), so an answer is always given as a band across it.
"""

from __future__ import annotations

from dataclasses import dataclass

#: hardness (MPa) that turns a dimensionless ``K`` into ``k = K / H``: ~300 HB (2940 MPa)
HARDNESS_MPA = 3000.0


@dataclass(frozen=True)
class Regime:
    """One lubrication regime's wear coefficient, mm³/(N·m) per flank.

    Attributes
    ----------
    name : str
        The ``[wear] regime`` value.
    low, nominal, high : float
        The band and the value used where the spec gives none (the band's geometric mean).
    source : str
        Where the numbers come from; an estimate says so.
    """

    name: str
    low: float
    nominal: float
    high: float
    source: str


def _regime(name: str, K_low: float, K_high: float, source: str) -> Regime:
    """A regime from the dimensionless band ``K_low``-``K_high``: ``k = K / H`` in
    mm²/N = mm³/(N·mm), times 1000 for mm³/(N·m)."""
    lo, hi = 1e3 * K_low / HARDNESS_MPA, 1e3 * K_high / HARDNESS_MPA
    return Regime(name, lo, (lo * hi) ** 0.5, hi, source)


REGIMES: dict[str, Regime] = {r.name: r for r in (
    _regime("oil", 3e-10, 3e-8,
            "estimate (K = 3e-10 to 3e-8): well below the 'K of 1e-6 or lower for mild "
            "lubricated conditions' (probsee.com/p/Wear_coefficient), so that an "
            "oil-lubricated coupling near its design angle keeps its teeth for years: a "
            "gear coupling's life is set by a gradual wear of its teeth (M. M. Calistrat, "
            "'What causes wear in gear-type couplings?', Koppers Co., Kop-Flex paper MMC8)"),
    _regime("grease", 3e-9, 3e-7,
            "estimate (K = 3e-9 to 3e-7): a decade above oil, as grease-lubricated gears "
            "wore faster than with oil in tests (ASME IDETC-CIE 2019, paper V010T11A041, "
            "abstract); the top still below the K = 1e-6 of mild lubricated wear"),
    _regime("dry", 1e-6, 1e-4,
            "published (K = 1e-6 to 1e-4): fretting wear (NPTEL, IIT course 112104122, "
            "lecture 7.5, Archard's constant by mechanism); dry sliding steels lie above "
            "(hard tool steel 1.3e-4, mild steel on mild steel 7e-3: "
            "en.wikipedia.org/wiki/Wear_coefficient, Table 1)"),
)}

DEFAULT_REGIME = "grease"  # gear couplings are mostly grease-packed


__all__ = ["DEFAULT_REGIME", "HARDNESS_MPA", "REGIMES", "Regime"]
