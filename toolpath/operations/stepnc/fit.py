"""Whether a workingstep's tool fits its feature, as ISO 14649 means it: a drill or reamer no wider
than the hole it makes, an end mill no wider than the hole, slot or rectangular pocket it clears.
A tool that does not fit is refused naming the tool, its diameter and the feature's size as written."""
from .errors import StepNcError
from .features import ClosedPocket, RectangularClosedProfile, RoundHole, Slot
from .model import Workingstep
from .process import BottomAndSideMilling, DrillingOperation

# Diameters compare with this much (mm) slack, for rounding in the file.
FIT_TOLERANCE = 1e-6


def feature_width(feature) -> tuple:
    """(the narrowest width a tool must pass, what it is called), or (None, None) when not known."""
    if isinstance(feature, RoundHole):
        return feature.diameter, "diameter"
    if isinstance(feature, Slot):
        return feature.width, "width"
    if isinstance(feature, ClosedPocket) and isinstance(feature.feature_boundary, RectangularClosedProfile):
        profile = feature.feature_boundary
        return min(profile.profile_width, profile.profile_length), "width"
    return None, None


def check_fit(step: Workingstep):
    """Refuse (StepNcError) a tool wider than the feature it makes; CENTER_DRILLING spots a hole
    with a tool that may be wider, so it is not checked."""
    operation, feature = step.its_operation, step.its_feature
    if isinstance(operation, DrillingOperation) and (operation.type_name == "CENTER_DRILLING"
                                                      or not isinstance(feature, RoundHole)):
        return
    if not isinstance(operation, (DrillingOperation, BottomAndSideMilling)):
        return
    width, called = feature_width(feature)
    tool = operation.its_tool
    diameter = tool.its_tool_body.dimension.diameter
    if width is None or diameter <= width + FIT_TOLERANCE:
        return
    what = f"MILLING_CUTTING_TOOL #{tool.id} '{tool.its_id}'"
    feature_name = f"{type(feature).__name__} #{feature.id} '{feature.its_id}'"
    if called == "diameter":
        raise StepNcError(f"{what}: diameter {diameter:g} mm is larger than the diameter {width:g} mm of "
                          f"{feature_name}; use a tool that fits the feature")
    raise StepNcError(f"{what}: diameter {diameter:g} mm is larger than the width {width:g} mm of "
                      f"{feature_name}; use a tool that fits the feature")
