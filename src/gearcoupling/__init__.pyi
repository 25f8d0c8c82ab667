# The public API, read by type checkers and, at run time, by lazy_loader.attach_stub: every
# name below is imported from its stage on first use, so ``import gearcoupling`` stays free
# of mesh, CAD, solver and viewer libraries (the pattern of scikit-image, SPEC 1).
from .clearance import SweepResult as SweepResult
from .clearance import binding_angle_deg as binding_angle_deg
from .clearance import contact_travel as contact_travel
from .clearance import critical_misalignment_deg as critical_misalignment_deg
from .clearance import design_quantities as design_quantities
from .clearance import double_engagement as double_engagement
from .clearance import min_backlash_rad as min_backlash_rad
from .clearance import sweep as sweep
from .errors import ArgumentError as ArgumentError
from .errors import BackendError as BackendError
from .errors import GearCouplingError as GearCouplingError
from .errors import GeometryError as GeometryError
from .errors import SpecError as SpecError
from .export import export_part as export_part
from .fea import FEContactResult as FEContactResult
from .fea import FESectorResult as FESectorResult
from .fea import fe_contact as fe_contact
from .fea import fe_contact_sector as fe_contact_sector
from .fea import mesh_part as mesh_part
from .fea import tooth_compliance_table as tooth_compliance_table
from .fea import write_mesh as write_mesh
from .geometry import FeedPath as FeedPath
from .geometry import feed_path as feed_path
from .geometry import hub_flank as hub_flank
from .geometry import inv as inv
from .geometry import inv_inverse as inv_inverse
from .geometry import sleeve_flank as sleeve_flank
from .geometry import transverse_section as transverse_section
from .hob import hob_program as hob_program
from .hob import measuring_charts as measuring_charts
from .inspection import compare_part as compare_part
from .interference import check_interference as check_interference
from .loading import LoadResult as LoadResult
from .loading import SectorCheck as SectorCheck
from .loading import body_windup_rad as body_windup_rad
from .loading import capacity as capacity
from .loading import capacity_curve as capacity_curve
from .loading import load as load
from .loading import load_from_sweep as load_from_sweep
from .loading import sector_check as sector_check
from .outputs import RunResult as RunResult
from .outputs import run as run
from .parts import build_part as build_part
from .parts import check_part as check_part
from .reporting import ReportResult as ReportResult
from .reporting import ReportSettings as ReportSettings
from .reporting import compare_capacity as compare_capacity
from .reporting import report as report
from .rotordynamics import CouplingData as CouplingData
from .rotordynamics import coupling_data as coupling_data
from .spec import CouplingSpec as CouplingSpec
from .spec import load_spec as load_spec
from .spec import spec_from_dict as spec_from_dict
from .spec import template_names as template_names
from .study import load_study as load_study
from .study import run_study as run_study
from .viewer import pose_state as pose_state
from .viewer import serve as serve
from .viewer import write_html as write_html

__version__: str
__all__: list[str]
