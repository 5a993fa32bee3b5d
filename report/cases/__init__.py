"""The report's validation cases, in the order the report shows them. Each module has
run(moreau, work, out, fast) -> CaseResult: it runs its scenes in `work`, writes its plots into
`out` and compares against its reference; `fast` is the subset `make test` affords."""
from . import (cantilever_convergence, cooks_membrane, cooks_membrane_incompressible, cylinder_re20_immersed, dam_break_surge,
               dzhanibekov_flip, flying_l, ghia_cavity, schafer_turek, sedimenting_disc, turek_hron_csm, turek_hron_fsi1,
               two_leaflet_valve)

CASES = [ghia_cavity, schafer_turek, cantilever_convergence, cooks_membrane, cooks_membrane_incompressible, flying_l,
         dzhanibekov_flip, dam_break_surge, turek_hron_csm, two_leaflet_valve, sedimenting_disc, cylinder_re20_immersed,
         turek_hron_fsi1]
