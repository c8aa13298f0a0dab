//! The problem as read from the input: nodes, elements, sets, materials, loads, functions and the
//! analysis settings. Indices are 0-based positions; labels are the numbers written in the file.

pub mod advice;
pub mod contact;
pub mod functions;
pub mod queries;
pub use contact::{
    ContactCondition, ContactSegment, Enforcement, Friction, Pairing, PenaltySource, SegmentKind,
};
pub use functions::TimeFunction;

use crate::error::Span;
use std::path::PathBuf;

/// DOF ids of OOFEM: 1 = u (x), 2 = v (y), 3 = w (z).
pub type DofId = u8;

/// Analysis type and its solver settings (spec §1.3).
#[derive(Debug, Clone)]
pub struct Analysis {
    pub kind: AnalysisKind,
    pub nsteps: usize,
    pub deltat: f64,
    /// StaticStructural `prescribedtimes` (overrides nsteps·deltat).
    pub prescribed_times: Option<Vec<f64>>,
    pub rtolf: f64,
    /// Displacement tolerance; <= 0 disables the test.
    pub rtold: f64,
    pub maxiter: usize,
    /// Recompute the tangent every k iterations; None = modified Newton (tangent at step start).
    pub manrmsteps: Option<usize>,
    /// NonLinearStatic: 0 total reference loads accumulated, 1 incremental.
    pub refloadmode: u8,
    /// Tangent predictor from prescribed-value increments, as the input gives it (`initialguess`);
    /// None: the analysis' default (see [`Analysis::predictor`]).
    pub initialguess: Option<bool>,
    pub errorcheck: bool,
    /// The time integration of a dynamic analysis.
    pub dynamics: Option<Dynamics>,
}

impl Analysis {
    /// Whether a step starts from the tangent predictor K Δu_f = −K_fp Δu_p of its prescribed
    /// increments: as `initialguess` says; else StaticStructural's default (yes) and OOFEM's
    /// NonLinearStatic and dynamic default (no: the increment is put on the prescribed DOFs
    /// alone), except that hertz takes the predictor in a static analysis whose tangent varies
    /// (`constant_structure` false: large deformation, a law with a state). There the boundary
    /// elements take the whole increment at once, in large deformation a strain of Δu/h that can
    /// invert them: a corrugated strip shortened by one element length a step was cut back at
    /// every step without the predictor (834 iterations for 5 steps), 3 iterations a step with
    /// it (`tests/suite/newton.rs`).
    /// Where the tangent is constant both converge to the same solution; OOFEM's iterates are
    /// kept there.
    pub fn predictor(&self, constant_structure: bool) -> bool {
        self.initialguess.unwrap_or(match self.kind {
            AnalysisKind::StaticStructural => true,
            AnalysisKind::NonLinearStatic => !constant_structure,
            _ => false,
        })
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnalysisKind {
    LinearStatic,
    NonLinearStatic,
    StaticStructural,
    /// Implicit dynamics, Newton in every time step (spec §1.2).
    NonLinearDynamic,
    /// OOFEM's linear implicit dynamics (spec §1.3), solved by NonLinearDynamic's engine: the
    /// same schemes and answers on a linear model, where OOFEM's total-displacement form and
    /// hertz's incremental Newton (one iteration) coincide; with large deformation, plasticity
    /// or contact the nonlinear problem is solved, not OOFEM's linearized one.
    DIIDynamic,
    /// Explicit dynamics, central differences with lumped mass (spec §1.4).
    NlDEIDynamic,
}

/// How a dynamic analysis integrates in time (`NonLinearDynamic`, spec §1.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dynamics {
    pub scheme: TimeScheme,
    /// Mass-proportional (Rayleigh) damping: C = eta·M.
    pub eta: f64,
    /// Stiffness-proportional (Rayleigh) damping `delta`: the force δ·Ḟ_int, the rate of the
    /// elements' internal forces by the scheme's velocity rule (δ·K·v on a linear model).
    pub delta: f64,
    /// hertz's `lumpedmass`: the lumped (HRZ) mass instead of the consistent one.
    pub lumped: bool,
    /// hertz's `keepcontactmass`: keep the mass of the contact nodes (OOFEM's way, which
    /// chatters and makes energy at impact) instead of moving it into the bodies.
    pub keep_contact_mass: bool,
}

/// OOFEM's `ddtScheme`: the kinematics of a step from its displacement increment Δu,
/// a = a0 Δu − a2 v − a3 a, v' = a1 Δu − a4 v − a5 a − a6 Δu_prev (spec §1.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TimeScheme {
    /// `ddtScheme 0` (OOFEM's default): three-point backward velocity with a Newmark-like
    /// acceleration; strongly dissipative, its first step backward Euler.
    ThreePointBackward,
    /// `ddtScheme 1`: backward Euler.
    BackwardEuler,
    /// `ddtScheme 2`: Newmark's family; γ = ½, β = ¼ is the trapezoidal rule (no dissipation).
    Newmark { gamma: f64, beta: f64 },
    /// hertz's `rhoinf ρ∞` on `ddtScheme 2`: Hilber–Hughes–Taylor, α = (ρ∞ − 1)/(ρ∞ + 1) ∈
    /// [−⅓, 0], γ = ½ − α, β = (1 − α)²/4: the forces of a step taken (1 + α) at its end and −α at
    /// its start, high frequencies damped to the spectral radius ρ∞, second order.
    Hht { alpha: f64 },
    /// `NlDEIDynamic`'s explicit central differences; the time step at most `reduct` times the
    /// stable one.
    CentralDifference { reduct: f64 },
}

impl TimeScheme {
    /// The constants a0..a6 for step size `dt`; `first`: no previous increment exists (the
    /// three-point scheme's first step is backward Euler).
    pub fn constants(self, dt: f64, first: bool) -> [f64; 7] {
        match self {
            TimeScheme::Hht { alpha } => TimeScheme::Newmark {
                gamma: 0.5 - alpha,
                beta: 0.25 * (1.0 - alpha) * (1.0 - alpha),
            }
            .constants(dt, first),
            TimeScheme::Newmark { gamma, beta } => [
                1.0 / (beta * dt * dt),
                gamma / (beta * dt),
                1.0 / (beta * dt),
                1.0 / (2.0 * beta) - 1.0,
                gamma / beta - 1.0,
                0.5 * dt * (gamma / beta - 2.0),
                0.0,
            ],
            TimeScheme::ThreePointBackward if !first => {
                [2.0 / (dt * dt), 1.5 / dt, 2.0 / dt, 0.0, 0.0, 0.0, 0.5 / dt]
            }
            _ => [1.0 / (dt * dt), 1.0 / dt, 1.0 / dt, 0.0, 0.0, 0.0, 0.0],
        }
    }
}

impl TimeScheme {
    /// HHT's α (0 for the other schemes): the step's equation is taken (1 + α) at its end and
    /// −α at its start.
    pub fn alpha(self) -> f64 {
        match self {
            TimeScheme::Hht { alpha } => alpha,
            _ => 0.0,
        }
    }
}

/// An `InitialCondition` record: values at the start of a dynamic analysis on the DOFs `dofs`
/// of the nodes of `set` (spec §1.6).
#[derive(Debug, Clone)]
pub struct InitialCondition {
    pub number: usize,
    pub set: usize,
    pub dofs: Vec<DofId>,
    pub displacement: Option<f64>,
    pub velocity: Option<f64>,
    pub acceleration: Option<f64>,
    pub span: Span,
}

/// Domain type (spec §1.5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DomainKind {
    PlaneStress,
    PlaneStrain,
    ThreeD,
    Truss2d,
    Truss1d,
}

impl DomainKind {
    /// Number of space dimensions.
    pub fn nsd(self) -> usize {
        match self {
            DomainKind::PlaneStress | DomainKind::PlaneStrain | DomainKind::Truss2d => 2,
            DomainKind::ThreeD => 3,
            DomainKind::Truss1d => 1,
        }
    }
    /// Default node DOF ids.
    pub fn default_dofs(self) -> &'static [DofId] {
        match self {
            DomainKind::PlaneStress | DomainKind::PlaneStrain => &[1, 2],
            DomainKind::ThreeD => &[1, 2, 3],
            DomainKind::Truss2d => &[1, 3],
            DomainKind::Truss1d => &[1],
        }
    }
}

/// Which steps, nodes and elements the `.out` file reports.
#[derive(Debug, Clone, Default)]
pub struct OutputSelection {
    pub tstep_all: bool,
    pub tstep_step: Option<usize>,
    pub tsteps_out: Vec<i64>,
    pub dofman_all: bool,
    pub dofman_output: Vec<i64>,
    pub dofman_except: Vec<i64>,
    pub element_all: bool,
    pub element_output: Vec<i64>,
    pub element_except: Vec<i64>,
}

impl OutputSelection {
    pub fn step(&self, n: usize) -> bool {
        self.tstep_all
            || self
                .tstep_step
                .is_some_and(|k| k > 0 && n.is_multiple_of(k))
            || self.tsteps_out.contains(&(n as i64))
    }
    pub fn node(&self, number: usize) -> bool {
        let n = number as i64;
        (self.dofman_all || self.dofman_output.contains(&n)) && !self.dofman_except.contains(&n)
    }
    pub fn element(&self, number: usize) -> bool {
        let n = number as i64;
        (self.element_all || self.element_output.contains(&n)) && !self.element_except.contains(&n)
    }
}

/// A node; slave nodes tie their DOFs to master nodes with weights.
#[derive(Debug, Clone)]
pub struct Node {
    pub label: usize,
    /// Coordinates padded to 3 components.
    pub coords: [f64; 3],
    pub slave: Option<SlaveLink>,
    pub span: Span,
}

/// `SlaveNode`: each DOF = Σ weight_i · (same DOF of master i).
#[derive(Debug, Clone)]
pub struct SlaveLink {
    /// Master node indices (0-based).
    pub masters: Vec<usize>,
    pub weights: Vec<f64>,
}

/// Element types (spec §1.9).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementType {
    Truss1d,
    Truss2d,
    PlaneStress2d,
    Quad1PlaneStrain,
    TrPlaneStress2d,
    TrPlaneStrain,
    QPlaneStress2d,
    /// 8-node quadrilateral, plane strain (OOFEM's QPlaneStrain).
    QPlaneStrain,
    /// 6-node triangle, plane stress (OOFEM's QTrPlaneStress2d, keyword `qtrplstr`).
    QTrPlaneStress2d,
    /// 6-node triangle, plane strain (OOFEM's QTrPlaneStrain).
    QTrPlaneStrain,
    LSpace,
    LTRSpace,
    LWedge,
    /// 10-node tetrahedron (OOFEM's QTRSpace): corners, then mid-edge nodes 1–2, 2–3, 3–1, 1–4, 2–4, 3–4.
    QTRSpace,
    /// 20-node serendipity brick (OOFEM's QSpace): corners as LSpace, then mid-edges 1–2, 2–3,
    /// 3–4, 4–1, 5–6, 6–7, 7–8, 8–5, 1–5, 2–6, 3–7, 4–8.
    QSpace,
    /// Axisymmetric 4-node quadrilateral (x = r, y = z, per radian).
    L4Axisymm,
    /// Axisymmetric 3-node triangle.
    Axisymm3d,
    /// Axisymmetric 8-node quadrilateral: corners, then mid-sides 1–2, 2–3, 3–4, 4–1.
    Q4Axisymm,
}

/// Where an axisymmetric element evaluates its hoop strain and its shear in small strain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HoopRule {
    /// At every integration point.
    Pointwise,
    /// At the element's centroid, whatever the point (OOFEM's L4Axisymm: ε_θ = Σ N_a(0) u_a /
    /// r_c, γ_rz from ∂N/∂x at the centroid; second order all the same).
    Centroid,
}

/// Strain/stress state of an element's material points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StressMode {
    PlaneStress,
    PlaneStrain,
    ThreeD,
    Uniaxial,
}

impl ElementType {
    pub const ALL: [(&'static str, ElementType); 18] = [
        ("truss1d", ElementType::Truss1d),
        ("truss2d", ElementType::Truss2d),
        ("planestress2d", ElementType::PlaneStress2d),
        ("quad1planestrain", ElementType::Quad1PlaneStrain),
        ("trplanestress2d", ElementType::TrPlaneStress2d),
        ("trplanestrain", ElementType::TrPlaneStrain),
        ("qplanestress2d", ElementType::QPlaneStress2d),
        ("qplanestrain", ElementType::QPlaneStrain),
        ("qtrplstr", ElementType::QTrPlaneStress2d),
        ("qtrplanestrain", ElementType::QTrPlaneStrain),
        ("lspace", ElementType::LSpace),
        ("ltrspace", ElementType::LTRSpace),
        ("lwedge", ElementType::LWedge),
        ("qtrspace", ElementType::QTRSpace),
        ("qspace", ElementType::QSpace),
        ("l4axisymm", ElementType::L4Axisymm),
        ("axisymm3d", ElementType::Axisymm3d),
        ("q4axisymm", ElementType::Q4Axisymm),
    ];

    pub fn from_keyword(k: &str) -> Option<ElementType> {
        Self::ALL.iter().find(|(n, _)| *n == k).map(|(_, t)| *t)
    }

    pub fn name(self) -> &'static str {
        match self {
            ElementType::Truss1d => "Truss1d",
            ElementType::Truss2d => "Truss2d",
            ElementType::PlaneStress2d => "PlaneStress2d",
            ElementType::Quad1PlaneStrain => "Quad1PlaneStrain",
            ElementType::TrPlaneStress2d => "TrPlaneStress2d",
            ElementType::TrPlaneStrain => "TrPlaneStrain",
            ElementType::QPlaneStress2d => "QPlaneStress2d",
            ElementType::QPlaneStrain => "QPlaneStrain",
            ElementType::QTrPlaneStress2d => "QTrPlStr",
            ElementType::QTrPlaneStrain => "QTrPlaneStrain",
            ElementType::LSpace => "LSpace",
            ElementType::LTRSpace => "LTRSpace",
            ElementType::LWedge => "LWedge",
            ElementType::QTRSpace => "QTRSpace",
            ElementType::QSpace => "QSpace",
            ElementType::L4Axisymm => "L4Axisymm",
            ElementType::Axisymm3d => "Axisymm3d",
            ElementType::Q4Axisymm => "Q4Axisymm",
        }
    }

    pub fn n_nodes(self) -> usize {
        match self {
            ElementType::Truss1d | ElementType::Truss2d => 2,
            ElementType::PlaneStress2d
            | ElementType::Quad1PlaneStrain
            | ElementType::LTRSpace
            | ElementType::L4Axisymm => 4,
            ElementType::TrPlaneStress2d | ElementType::TrPlaneStrain | ElementType::Axisymm3d => 3,
            ElementType::QPlaneStress2d
            | ElementType::QPlaneStrain
            | ElementType::LSpace
            | ElementType::Q4Axisymm => 8,
            ElementType::QTrPlaneStress2d | ElementType::QTrPlaneStrain | ElementType::LWedge => 6,
            ElementType::QTRSpace => 10,
            ElementType::QSpace => 20,
        }
    }

    pub fn mode(self) -> StressMode {
        match self {
            ElementType::Truss1d | ElementType::Truss2d => StressMode::Uniaxial,
            ElementType::PlaneStress2d
            | ElementType::TrPlaneStress2d
            | ElementType::QPlaneStress2d
            | ElementType::QTrPlaneStress2d => StressMode::PlaneStress,
            // Axisymmetric elements: the material sees (ε_rr, ε_zz, ε_θθ, γ_rz) as plane strain's
            // four components, the hoop strain in the out-of-plane place.
            ElementType::Quad1PlaneStrain
            | ElementType::TrPlaneStrain
            | ElementType::QPlaneStrain
            | ElementType::QTrPlaneStrain
            | ElementType::L4Axisymm
            | ElementType::Axisymm3d
            | ElementType::Q4Axisymm => StressMode::PlaneStrain,
            ElementType::LSpace
            | ElementType::LTRSpace
            | ElementType::LWedge
            | ElementType::QTRSpace
            | ElementType::QSpace => StressMode::ThreeD,
        }
    }

    /// Reference shape of the element.
    pub fn shape(self) -> crate::fem::Shape {
        use crate::fem::Shape;
        match self {
            ElementType::Truss1d | ElementType::Truss2d => Shape::Line2,
            ElementType::PlaneStress2d | ElementType::Quad1PlaneStrain | ElementType::L4Axisymm => {
                Shape::Quad4
            }
            ElementType::TrPlaneStress2d | ElementType::TrPlaneStrain | ElementType::Axisymm3d => {
                Shape::Tri3
            }
            ElementType::QPlaneStress2d | ElementType::QPlaneStrain | ElementType::Q4Axisymm => {
                Shape::Quad8
            }
            ElementType::QTrPlaneStress2d | ElementType::QTrPlaneStrain => Shape::Tri6,
            ElementType::LSpace => Shape::Hexa8,
            ElementType::LTRSpace => Shape::Tet4,
            ElementType::LWedge => Shape::Wedge6,
            ElementType::QTRSpace => Shape::Tet10,
            ElementType::QSpace => Shape::Hexa20,
        }
    }

    /// Default number of integration points.
    pub fn default_nip(self) -> usize {
        match self {
            ElementType::Truss1d | ElementType::Truss2d => 1,
            ElementType::TrPlaneStress2d
            | ElementType::TrPlaneStrain
            | ElementType::LTRSpace
            | ElementType::Axisymm3d => 1,
            ElementType::L4Axisymm | ElementType::Q4Axisymm => 4,
            ElementType::PlaneStress2d
            | ElementType::Quad1PlaneStrain
            | ElementType::QPlaneStress2d
            | ElementType::QPlaneStrain
            | ElementType::QTrPlaneStress2d
            | ElementType::QTrPlaneStrain => 4,
            ElementType::LSpace => 8,
            ElementType::LWedge => 6,
            // OOFEM's QTRSpace: 4 points (exact for its linear-elastic stiffness).
            ElementType::QTRSpace => 4,
            // OOFEM's QSpace: 27 points.
            ElementType::QSpace => 27,
        }
    }

    pub fn is_truss(self) -> bool {
        matches!(self, ElementType::Truss1d | ElementType::Truss2d)
    }

    /// An axisymmetric element: x is the radius r, y the axis z, and every integral is per
    /// radian (weighted by r, as OOFEM's).
    pub fn is_axisymmetric(self) -> bool {
        matches!(
            self,
            ElementType::L4Axisymm | ElementType::Axisymm3d | ElementType::Q4Axisymm
        )
    }

    /// How an axisymmetric element takes its hoop strain u_r/r and its shear γ_rz in small
    /// strain (None for the others).
    pub fn hoop_rule(self) -> Option<HoopRule> {
        match self {
            ElementType::L4Axisymm => Some(HoopRule::Centroid),
            // OOFEM's Q4Axisymm takes them at the centroid too (`nipfish 1`; any other value
            // leaves its B matrix empty), which makes the 8-node element converge at first
            // order (a spherical shell: −5.8, −2.9, −1.4 % on 4, 8, 16 elements a side): its
            // QUIRK. hertz takes them at every point (fourth order).
            ElementType::Axisymm3d | ElementType::Q4Axisymm => Some(HoopRule::Pointwise),
            _ => None,
        }
    }
}

/// An element as read: type, node indices (0-based), section/material and options.
#[derive(Debug, Clone)]
pub struct Element {
    pub label: usize,
    pub etype: ElementType,
    pub nodes: Vec<usize>,
    pub cross_section: usize,
    pub material: usize,
    pub nip: Option<usize>,
    pub nlgeo: bool,
    /// Every point takes the element's mean volumetric strain (B-bar, F-bar; OOFEM's `LSpaceBB`,
    /// hertz's `Quad1PlaneStrainBB`): no volumetric locking of the linear quadrilateral and
    /// brick.
    pub bbar: bool,
    /// Truss2d plane: 0 = x–z (default), 1 = x–y, 2 = y–z.
    pub truss_plane: u8,
    pub span: Span,
}

impl Element {
    /// OOFEM's keyword of the element: its type's, with `BB` for a barred one.
    pub fn keyword(&self) -> String {
        match self.bbar {
            true => format!("{}BB", self.etype.name()),
            false => self.etype.name().to_string(),
        }
    }

    /// The nodes of its boundary `b` (OOFEM's number, from 1: an edge of a 2D element, a face
    /// of a 3D one), in its shape's order.
    pub fn boundary_nodes(&self, b: usize) -> Vec<usize> {
        let local = self.etype.shape().boundaries()[b - 1];
        local.iter().map(|&a| self.nodes[a]).collect()
    }

    /// The DOF ids every node of this element carries, in element order.
    pub fn dof_ids(&self) -> &'static [DofId] {
        match self.etype {
            ElementType::Truss1d => &[1],
            ElementType::Truss2d => match self.truss_plane {
                1 => &[1, 2],
                2 => &[2, 3],
                _ => &[1, 3],
            },
            t if t.mode() == StressMode::ThreeD => &[1, 2, 3],
            _ => &[1, 2],
        }
    }
}

/// `SimpleCS` cross section.
#[derive(Debug, Clone)]
pub struct CrossSection {
    pub thick: Option<f64>,
    pub area: f64,
    pub material: Option<usize>,
    pub set: Option<usize>,
}

/// A material record.
#[derive(Debug, Clone)]
pub struct Material {
    pub density: f64,
    pub talpha: f64,
    pub law: MaterialLaw,
}

/// `MisesMat`'s parameters: isotropic elasticity, the von Mises yield condition with isotropic
/// hardening, linear kinematic hardening and damage.
#[derive(Debug, Clone, PartialEq)]
pub struct Mises {
    pub young: f64,
    pub poisson: f64,
    /// The yield stress against κ, the equivalent (accumulated) plastic strain.
    pub hardening: Hardening,
    /// Linear kinematic (Prager) hardening modulus `hk`, a hertz extension: the back stress
    /// grows by (2/3)·hk·dε_p (uniaxially hk·dε_p). 0: none.
    pub kinematic: f64,
    /// Damage ω(κ) = ω_c·(1 − e^(−aκ)), σ = (1 − ω)·σ_eff (`omega_crit`, `a`).
    pub damage: Option<Damage>,
}

/// Isotropic hardening of `MisesMat`: σ_y(κ).
#[derive(Debug, Clone, PartialEq)]
pub enum Hardening {
    /// `htype 0`: σ_y = sig0 + H·κ (H < 0 softens).
    Linear { sig0: f64, modulus: f64 },
    /// `htype 1`: piecewise linear through (`h_eps`, `h(eps)`), the first κ 0.
    Table { kappa: Vec<f64>, stress: Vec<f64> },
}

/// `MisesMat`'s damage parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Damage {
    /// ω_c (`omega_crit`), the damage approached as κ grows.
    pub critical: f64,
    /// a, the rate in κ.
    pub rate: f64,
}

/// The constitutive law of a material record.
#[derive(Debug, Clone)]
pub enum MaterialLaw {
    /// `IsoLE`: isotropic linear elasticity (St. Venant–Kirchhoff with `nlgeo 1`).
    LinearElastic { young: f64, poisson: f64 },
    /// `MooneyRivlinCompressibleMat`: W = C₁(J^{−2/3} I₁ − 3) + C₂(J^{−4/3} I₂ − 3) + ½K(ln J)².
    MooneyRivlin { c1: f64, c2: f64, k: f64 },
    /// `OgdenCompressibleMat`: W = Σ_p μ_p/α_p (J^{−α_p/3} Σ_a λ_a^{α_p} − 3) + ½K(ln J)².
    Ogden {
        alpha: Vec<f64>,
        mu: Vec<f64>,
        k: f64,
    },
    /// `SimoPisterMat`: W = ½G(I₁ − 3) − G ln J + ½k(ln J)².
    SimoPister { g: f64, k: f64 },
    /// `MisesMat`: von Mises plasticity.
    Mises(Mises),
    /// Upstream OOFEM's `DummyMat` of contact elements: no mechanical law (a bulk element with
    /// it is an input error).
    Dummy,
}

impl MaterialLaw {
    /// The small-strain shear and bulk moduli (G, K) of a hyperelastic law (its tangent at
    /// F = I; Simo–Pister's `k` is Lamé's λ there, so its K is k + 2G/3); None for the others.
    pub fn hyperelastic_moduli(&self) -> Option<(f64, f64)> {
        match self {
            MaterialLaw::MooneyRivlin { c1, c2, k } => Some((2.0 * (c1 + c2), *k)),
            MaterialLaw::Ogden { alpha, mu, k } => Some((
                0.5 * alpha.iter().zip(mu).map(|(a, m)| a * m).sum::<f64>(),
                *k,
            )),
            MaterialLaw::SimoPister { g, k } => Some((*g, k + 2.0 * g / 3.0)),
            _ => None,
        }
    }
}

impl Material {
    /// Young's modulus (of the small-strain limit for a hyperelastic law).
    pub fn young(&self) -> f64 {
        match &self.law {
            MaterialLaw::LinearElastic { young, .. } | MaterialLaw::Mises(Mises { young, .. }) => {
                *young
            }
            MaterialLaw::Dummy => 0.0,
            law => {
                let (g, k) = law.hyperelastic_moduli().expect("a hyperelastic law");
                9.0 * k * g / (3.0 * k + g)
            }
        }
    }

    /// Poisson's ratio (of the small-strain limit for a hyperelastic law).
    pub fn poisson(&self) -> f64 {
        match &self.law {
            MaterialLaw::LinearElastic { poisson, .. }
            | MaterialLaw::Mises(Mises { poisson, .. }) => *poisson,
            MaterialLaw::Dummy => 0.0,
            law => {
                let (g, k) = law.hyperelastic_moduli().expect("a hyperelastic law");
                (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g))
            }
        }
    }
}

/// Dirichlet condition: values per DOF id on the nodes of a set, scaled by a time function.
#[derive(Debug, Clone)]
pub struct Dirichlet {
    pub number: usize,
    pub function: usize,
    pub dofs: Vec<DofId>,
    pub values: Vec<f64>,
    pub set: Option<usize>,
    /// The record, for messages.
    pub span: Span,
}

impl Dirichlet {
    /// Prescribed value factor for a DOF id (OOFEM: index of the id in `dofs`, else the first).
    pub fn value_for(&self, dof: DofId) -> f64 {
        let i = self.dofs.iter().position(|&d| d == dof).unwrap_or(0);
        self.values.get(i).copied().unwrap_or(0.0)
    }
}

/// Loads: nodal forces, edge/surface tractions, body forces.
#[derive(Debug, Clone)]
pub enum LoadKind {
    Nodal,
    Edge,
    Surface,
    DeadWeight,
}

impl LoadKind {
    /// The record keyword, for messages.
    pub fn record_name(&self) -> &'static str {
        match self {
            LoadKind::Nodal => "NodalLoad",
            LoadKind::Edge => "ConstantEdgeLoad",
            LoadKind::Surface => "ConstantSurfaceLoad",
            LoadKind::DeadWeight => "DeadWeight",
        }
    }
}

#[derive(Debug, Clone)]
pub struct Load {
    pub number: usize,
    pub kind: LoadKind,
    pub function: usize,
    /// DOF ids the components act on (DeadWeight: 1..nsd).
    pub dofs: Vec<DofId>,
    pub components: Vec<f64>,
    pub set: usize,
    /// `csType 1`: the components are in the boundary's own axes, the normal one outward (a 2D
    /// edge: OOFEM's, the second along the outward normal, the first along its turn by −90°; a
    /// 3D face: the third along the outward normal, the first horizontal, as OOFEM's `LSpace`).
    pub local: bool,
    /// `follower` (hertz's): a `csType 1` traction on the current boundary, per current length
    /// or area, instead of on the reference one (a pressure that turns and stretches with the
    /// surface in large deformation; see [`crate::solid::follower`]).
    pub follower: bool,
    /// The record, for messages.
    pub span: Span,
}

impl Load {
    /// The element boundaries a traction acts on, as (element index, local node numbers).
    ///
    /// An edge load acts on `elementedges` and on the `elementboundaries` of 2D elements (the
    /// boundary of a 2D element is an edge: what a Gmsh physical curve becomes); a surface load
    /// on `elementsurfaces` and the `elementboundaries` of 3D elements. A set entity the load
    /// cannot act on (a face under an edge load, an edge under a surface load), or a set with
    /// nothing to act on, is an error: a load that silently applies nothing is a wrong answer.
    /// Nodal loads and dead weight have no boundaries (an empty list).
    pub fn boundaries(
        &self,
        set: &Set,
        elements: &[Element],
    ) -> std::result::Result<Vec<(usize, &'static [usize])>, String> {
        let dim = |e: usize| elements[e].etype.shape().dim();
        let label = |e: usize| elements[e].label;
        let name = self.kind.record_name();
        let mut out = Vec::new();
        match self.kind {
            LoadKind::Nodal | LoadKind::DeadWeight => return Ok(out),
            LoadKind::Edge => {
                if let Some(&(e, _)) = set.surfaces.first() {
                    return Err(format!(
                        "{name} {} acts on set {}, whose `elementsurfaces` name faces (element {}): \
                         an edge load acts on `elementedges`, or on `elementboundaries` of 2D elements; \
                         use ConstantSurfaceLoad on faces",
                        self.number,
                        self.set,
                        label(e)
                    ));
                }
                for &(e, b) in &set.edges {
                    out.push((e, elements[e].etype.shape().edges()[b - 1]));
                }
                for &(e, b) in &set.boundaries {
                    if dim(e) != 2 {
                        return Err(format!(
                            "{name} {} acts on set {}, whose `elementboundaries` name faces of 3D \
                             element {}: an edge load acts on edges (`elementedges` in 3D); use \
                             ConstantSurfaceLoad on faces",
                            self.number,
                            self.set,
                            label(e)
                        ));
                    }
                    out.push((e, elements[e].etype.shape().boundaries()[b - 1]));
                }
            }
            LoadKind::Surface => {
                let faces = set.boundaries.iter().chain(&set.surfaces);
                if let Some(&(e, _)) = set.edges.first() {
                    return Err(format!(
                        "{name} {} acts on set {}, whose `elementedges` name edges (element {}): \
                         a surface load acts on faces of 3D elements; use ConstantEdgeLoad on edges",
                        self.number,
                        self.set,
                        label(e)
                    ));
                }
                for &(e, b) in faces {
                    if dim(e) != 3 {
                        return Err(format!(
                            "{name} {} acts on set {}, which names boundaries of {}D element {}: a \
                             surface load acts on faces of 3D elements; use ConstantEdgeLoad on the \
                             edges of 2D elements",
                            self.number,
                            self.set,
                            dim(e),
                            label(e)
                        ));
                    }
                    out.push((e, elements[e].etype.shape().boundaries()[b - 1]));
                }
            }
        }
        Ok(out)
    }

    /// Why this load would act on nothing, if it would: its set has none of what it acts on.
    /// `boundaries`: what [`Load::boundaries`] found in `set`.
    pub fn acts_on_nothing(
        &self,
        set: &Set,
        boundaries: &[(usize, &'static [usize])],
    ) -> Option<String> {
        let (empty, what) = match self.kind {
            LoadKind::Nodal => (set.nodes.is_empty(), "no nodes"),
            LoadKind::DeadWeight => (set.elements.is_empty(), "no elements"),
            LoadKind::Edge => (
                boundaries.is_empty(),
                "no element edges (`elementedges`, or `elementboundaries` of 2D elements)",
            ),
            LoadKind::Surface => (
                boundaries.is_empty(),
                "no element faces (`elementboundaries` or `elementsurfaces` of 3D elements)",
            ),
        };
        empty.then(|| {
            format!(
                "{} {} acts on set {}, which has {what}: it would apply nothing",
                self.kind.record_name(),
                self.number,
                self.set
            )
        })
    }
}

/// `Set` record (spec §1.16), resolved to 0-based indices.
#[derive(Debug, Clone, Default)]
pub struct Set {
    /// Node list: sorted unique union, or input order with `ordered_nodes`.
    pub nodes: Vec<usize>,
    pub elements: Vec<usize>,
    /// (element index, boundary number 1-based).
    pub boundaries: Vec<(usize, usize)>,
    pub edges: Vec<(usize, usize)>,
    pub surfaces: Vec<(usize, usize)>,
    /// Upstream OOFEM contact elements listed in `elements` (indices into the model's).
    pub contact_elements: Vec<usize>,
    /// Nodes its `nodes` and `noderanges` give more than once (a contact condition refuses them
    /// as it refuses a node listed twice in its own `nodeset`).
    pub repeated: Vec<usize>,
    /// hertz's `name "text"` (a Gmsh physical group's name, written by `hertz import` and
    /// `@gmsh`): unique among the model's sets.
    pub name: Option<String>,
}

/// The whole problem.
#[derive(Debug, Clone)]
pub struct Model {
    pub input_path: PathBuf,
    pub output_name: String,
    pub description: String,
    pub analysis: Analysis,
    pub domain: DomainKind,
    pub output: OutputSelection,
    pub nodes: Vec<Node>,
    pub elements: Vec<Element>,
    pub cross_sections: Vec<CrossSection>,
    pub materials: Vec<Material>,
    pub dirichlet: Vec<Dirichlet>,
    pub loads: Vec<Load>,
    pub functions: Vec<TimeFunction>,
    pub sets: Vec<Set>,
    pub segments: Vec<ContactSegment>,
    pub contacts: Vec<ContactCondition>,
    pub initial_conditions: Vec<InitialCondition>,
}

impl Model {
    /// The number (from 1) of the set named `name` (hertz's `name` on a set record).
    pub fn set_named(&self, name: &str) -> Option<usize> {
        self.sets
            .iter()
            .position(|s| s.name.as_deref() == Some(name))
            .map(|i| i + 1)
    }

    /// Times of steps 1..=n (spec §1.3).
    pub fn step_times(&self) -> Vec<f64> {
        let a = &self.analysis;
        match a.kind {
            AnalysisKind::LinearStatic => (1..=a.nsteps).map(|n| n as f64).collect(),
            AnalysisKind::NonLinearStatic => (0..a.nsteps).map(|n| n as f64 * a.deltat).collect(),
            AnalysisKind::NonLinearDynamic
            | AnalysisKind::DIIDynamic
            | AnalysisKind::NlDEIDynamic => (1..=a.nsteps).map(|n| n as f64 * a.deltat).collect(),
            AnalysisKind::StaticStructural => match &a.prescribed_times {
                Some(t) => t.clone(),
                None => (1..=a.nsteps).map(|n| n as f64 * a.deltat).collect(),
            },
        }
    }

    /// Whether a load follows the boundary it acts on (its force depends on the state).
    pub fn has_follower_loads(&self) -> bool {
        self.loads.iter().any(|l| l.follower)
    }
}
