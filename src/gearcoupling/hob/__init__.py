"""Manufacturing: hob feed programs and measuring-machine charts (geometry level).

Pure numpy kernels over the feed path and the exact hub flank; writers and plots import
matplotlib lazily.
"""

from .program import HobProgram, Move, hob_program

__all__ = ["HobProgram", "Move", "hob_program"]
