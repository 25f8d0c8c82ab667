"""The load analysis' numerical kernels (numpy and scipy over arrays, no solver at run time):

- :mod:`.halfspace`: contact pressure on a half-space (influence matrices, the contact solve);
- :mod:`.gapfield`: the gap between the flanks over a developed grid of each tooth;
- :mod:`.cantilever`: tapered Timoshenko tooth cantilevers with Weber's foundation;
- :mod:`.fitted`: the FE tooth table's far field by the shipped fit (``fitted.json``);
- :mod:`.windup`: the exact wind-up of linear tooth springs (piecewise linear in the wind-up).
"""
