"""gearcoupling: crowned-tooth gear couplings, from a parameter file to exact geometry.

Every public name (``gc.__all__``) is a plain function or class, listed with its stage in
``__init__.pyi`` and imported from there on first use, so ``import gearcoupling`` loads no
mesh, CAD, solver or viewer library. Units, frames, signs and names:
``docs/conventions.md``; every public name by stage: ``docs/api.md``.
"""

# first: the program's signal handler before the imports below (``gearcoupling ...`` only)
from . import interrupts as _interrupts

_interrupts.at_program_start()

import lazy_loader  # noqa: E402

__version__ = "0.1.0"

__getattr__, __dir__, __all__ = lazy_loader.attach_stub(__name__, __file__)
