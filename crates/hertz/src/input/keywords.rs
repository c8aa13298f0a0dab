//! The record keywords of each block of an input file: from them the cursor knows which block
//! a record belongs to, and the readers what they support.

/// Material record keywords.
pub(super) const MATERIAL_KEYWORDS: [&str; 5] = [
    "isole",
    "misesmat",
    "mooneyrivlincompressiblemat",
    "ogdencompressiblemat",
    "simopistermat",
];

/// Time-function record keywords.
pub(super) const FUNCTION_KEYWORDS: [&str; 3] =
    ["constantfunction", "piecewiselinfunction", "peakfunction"];

/// Boundary condition and load records (keywords compare case-insensitively).
pub(super) const LOAD_KEYWORDS: [&str; 6] = [
    "BoundaryCondition",
    "NodalLoad",
    "ConstantEdgeLoad",
    "ConstantSurfaceLoad",
    "ConstantPressureLoad",
    "DeadWeight",
];

/// The upstream OOFEM contact condition record.
pub(super) const UPSTREAM_CONDITION: &str = "StructuralPenaltyContactBC";

/// Records of the boundary-condition block that hertz reads but refuses with a message of their
/// own (not offered as supported).
pub(super) const REFUSED_CONDITIONS: [&str; 1] = ["ConstantPressureLoad"];

/// The boundary-condition block's supported records, from the keyword tables.
pub(super) fn supported_conditions() -> String {
    LOAD_KEYWORDS
        .iter()
        .filter(|k| !REFUSED_CONDITIONS.contains(k))
        .copied()
        .chain(super::contact::CONDITION_KEYWORDS)
        .chain([UPSTREAM_CONDITION])
        .collect::<Vec<_>>()
        .join(", ")
}

/// Whether `kw` (lower case) is a record of the boundary-condition block.
pub(super) fn is_condition(kw: &str) -> bool {
    LOAD_KEYWORDS.iter().any(|k| k.eq_ignore_ascii_case(kw))
        || super::contact::CONDITION_KEYWORDS.contains(&kw)
        || UPSTREAM_CONDITION.eq_ignore_ascii_case(kw)
}
