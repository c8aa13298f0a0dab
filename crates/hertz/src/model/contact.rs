//! Contact segments and contact conditions as read from the input (spec §2).

use crate::error::Span;

/// What a node can come into contact with.
#[derive(Debug, Clone)]
pub enum SegmentKind {
    /// Edges of 2D elements, (element index, boundary number): straight for linear elements,
    /// quadratic (3 nodes) for QPlaneStress2d.
    Edges { edges: Vec<(usize, usize)> },
    /// Faces of 3D elements, (element index, boundary number): triangles and bilinear
    /// quadrilaterals of LSpace, LTRSpace, LWedge.
    Faces { faces: Vec<(usize, usize)> },
    /// Rigid circle (2D) or sphere (3D); the body is the disk/ball, or everything outside it with
    /// `cavity`. With `node`, the centre moves with that node's displacement (load or prescribe
    /// the node to drive the indenter).
    Circle {
        center: [f64; 3],
        radius: f64,
        node: Option<usize>,
        cavity: bool,
    },
    /// Rigid curve y = Σ a_i x^(k−1−i) (highest power first), 2D; the body is below the curve, or
    /// above it with `bodyabove`.
    Polynomial { coeffs: Vec<f64>, body_above: bool },
    /// Rigid line (2D) or plane (3D) through `point` with unit `normal` pointing out of the rigid
    /// body; with `node`, it translates with that node (hertz extension: `planecontactsegment`).
    Plane {
        point: [f64; 3],
        normal: [f64; 3],
        node: Option<usize>,
    },
}

#[derive(Debug, Clone)]
pub struct ContactSegment {
    pub number: usize,
    pub kind: SegmentKind,
    pub span: Span,
}

/// How a condition enforces non-penetration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Enforcement {
    /// A penalty ε: the force per length of penetration (per contact node; for mortar per unit
    /// area, a pressure).
    Penalty(PenaltySource),
    /// Lagrange multipliers: one unknown per contact node (and friction's components).
    Multipliers,
}

/// Where a condition's penalty comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PenaltySource {
    /// `penalty p` in its record.
    Given(f64),
    /// None given (hertz extension): each contact node's from the stiffness of the elements
    /// under it (`contact::law::penalty::from_mesh`, one rule for every formulation).
    FromMesh,
}

impl Enforcement {
    /// Whether a condition with this enforcement and `friction` has its contact forces as
    /// unknowns of the Newton system: with Lagrange multipliers, and with a penalty and
    /// friction, whose forces are solved as multipliers with the penalty's compliance (see
    /// `contact::law::multiplier`): the same solution, and a Newton iteration that does not
    /// carry the penalty times the gap error of each iterate into the friction force.
    pub fn forces_are_unknowns(self, friction: Option<Friction>) -> bool {
        self == Enforcement::Multipliers || friction.is_some()
    }
}

/// Which nodes meet what.
#[derive(Debug, Clone)]
pub enum Pairing {
    /// Fixed (master, slave) node pairs.
    NodeToNode { pairs: Vec<(usize, usize)> },
    /// Every node meets the closest of the segments it projects onto.
    NodeToSegment {
        nodes: Vec<usize>,
        segments: Vec<usize>,
    },
    /// Mortar: the slave segment's edges meet the master segments in a weak sense.
    Mortar { slave: usize, segments: Vec<usize> },
}

/// Coulomb friction of a condition: regularized by a tangential penalty (the stick stiffness), or
/// (Lagrange multipliers) exact, with the friction force a multiplier too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    /// Coefficient of friction μ ≥ 0.
    pub mu: f64,
    /// Tangential penalty ε_T (force per length of elastic slip, like `penalty`): `pt`, or
    /// None for the normal penalty in effect (and with multipliers, which have none).
    pub penalty: Option<f64>,
}

#[derive(Debug, Clone)]
pub struct ContactCondition {
    /// BC record number.
    pub number: usize,
    pub enforcement: Enforcement,
    /// Coulomb friction (node-to-segment and mortar penalty conditions, node-to-segment
    /// multiplier conditions).
    pub friction: Option<Friction>,
    pub pairing: Pairing,
    /// Prescribed unit normal (N2N: instead of the initial master-to-slave direction; N2S:
    /// instead of the segment normal).
    pub normal: Option<[f64; 3]>,
    /// Per contact node, the factor of the penalties (node-to-segment; upstream OOFEM's contact
    /// BC counts a node once per slave element); None: 1.
    pub node_weights: Option<Vec<f64>>,
    /// Past an open boundary of the master, a node's force fades over its tributary extent (the
    /// default), or within 1 % of the boundary edge (upstream OOFEM input, whose slave points must
    /// project onto the master).
    pub tributary_ramp: bool,
    pub span: Span,
}
