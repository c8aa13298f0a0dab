//! The vocabulary every contact formulation shares: what a node is paired with ([`Partner`]),
//! its state after an evaluation ([`SlotState`]) and friction history ([`Anchor`]), how partners
//! are searched ([`Search`]), the state a formulation is evaluated at ([`Ctx`]) and the local
//! unknowns of a point ([`Local`]), the [`Formulation`] trait, and the glue from a law to a
//! point ([`apply_law`]).

use super::dual::{self, DVec, Dual};
use super::geometry::bodies::Inside;
use super::law::{self, Laws};
use super::slot::SlotLinearization;
use crate::assembly::NodalState;
use crate::error::Result;
use crate::model::queries::model_size;
use crate::model::Model;

/// What a contact node is paired with at the current state (the contact point itself is
/// recomputed at every evaluation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Partner {
    None,
    /// A fixed master node (node-to-node).
    Node(usize),
    /// An edge of the condition's master surface (index into its edges).
    Edge(usize),
    /// A face of the condition's master surface (index into its faces).
    Face(usize),
    /// A rigid segment (model segment index).
    Rigid(usize),
}

/// Contact state of one contact node after an evaluation.
#[derive(Debug, Clone)]
pub struct SlotState {
    /// BC record number of the condition.
    pub condition: usize,
    pub node: usize,
    pub partner: Partner,
    /// Contact point parameters on the partner (edge s ∈ [0, 1], face (ξ, η), polynomial
    /// abscissa; unused ones 0).
    pub xi: [f64; 2],
    /// Signed gap (NaN without a partner).
    pub gap: f64,
    /// Normal contact force on the node (≥ 0 in compression).
    pub force: f64,
    pub pressure: f64,
    /// The area the force is spread over (the node's tributary area; mortar: its support D_j),
    /// so that `pressure` is `force / area`; 0 where none is known.
    pub area: f64,
    pub active: bool,
    /// Current node position.
    pub x: [f64; 3],
    /// Boundary weight of the contact point (1 on its partner, less past an open end or edge).
    pub weight: f64,
    /// Its constraint repeats one of another condition (two-pass contact with multipliers) and
    /// is dropped, or it is in a self-contact pair held by one merged constraint
    /// ([`crate::contact::repeated`]; node-to-segment marks the pair's second node, mortar
    /// both).
    pub repeated: bool,
    /// Friction of a closed point: stick (else slip) and the friction force's magnitude.
    pub friction: Option<(bool, f64)>,
    /// Friction history this state leaves if it is the converged one: the anchor for the next
    /// step (None: no partner, or no friction).
    pub anchor: Option<Anchor>,
    /// The node lies inside an element of its master's body with no force holding it: it has
    /// crossed the master surface where no partner measures it (past an end or a crease). A
    /// converged state must have none (see [`crate::solve`]).
    pub crossed: Option<Inside>,
    /// How deep the node lies behind the other wall of a repeated pair whose one constraint
    /// does not hold it (see [`crate::contact::repeated::unheld`]). A converged state must have
    /// none.
    pub unheld: Option<f64>,
    /// How much the partner surface bends at the partner's corner nearest the contact point:
    /// 1 − n̂·n there, n̂ the smoothed normal the gap is measured along and n the partner's own
    /// (0 on a flat part, 0.29 at a right-angled corner; 0 where not known). Of two nodes of
    /// one self-contact surface at one place, the one meeting the flatter part holds the
    /// contact (see [`crate::contact::repeated::BEND_APART`]).
    pub bend: f64,
    /// The contact point on the partner (node-to-segment against an edge or face): two nodes
    /// each near the other's contact point hold one contact, open or closed.
    pub point: Option<[f64; 3]>,
}

impl SlotState {
    /// The state of condition `condition`'s contact node `node` at `x` before its evaluation:
    /// no partner, no force.
    pub fn unpaired(condition: usize, node: usize, x: [f64; 3]) -> SlotState {
        SlotState {
            condition,
            node,
            partner: Partner::None,
            xi: [f64::NAN; 2],
            gap: f64::NAN,
            force: 0.0,
            pressure: 0.0,
            area: 0.0,
            active: false,
            x,
            weight: 1.0,
            repeated: false,
            friction: None,
            anchor: None,
            crossed: None,
            unheld: None,
            bend: 0.0,
            point: None,
        }
    }
}

/// The master's material point a frictional contact node sticks to (the friction history).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// The partner the point belongs to (an edge, or a rigid segment).
    pub partner: Partner,
    /// Its parameter on an edge.
    pub xi: [f64; 2],
    /// Its position relative to a rigid segment's origin (which moves with the segment's node).
    pub offset: [f64; 3],
}

/// How partners are found in an evaluation.
#[derive(Debug, Clone, Copy)]
pub enum Search<'a> {
    /// Search every node.
    Fresh,
    /// Search, but keep a node's previous partner while it remains valid (hysteresis: a node on a
    /// vertex does not alternate between the two edges).
    Hint(&'a [SlotState]),
    /// Keep the given partners (the finite-difference tests: the tangent is the derivative of the
    /// residual at fixed partners, with the contact point still moving).
    Frozen(&'a [SlotState]),
}

impl<'a> Search<'a> {
    /// The same search restricted to one formulation's states.
    pub(super) fn slice(&self, range: std::ops::Range<usize>) -> Search<'a> {
        match *self {
            Search::Fresh => Search::Fresh,
            Search::Hint(s) => Search::Hint(&s[range]),
            Search::Frozen(s) => Search::Frozen(&s[range]),
        }
    }

    /// Whether slot k's constraint was merged into another's at the previous state (see
    /// `contact::n2s::pairs`).
    pub fn repeated(&self, k: usize) -> bool {
        match self {
            Search::Fresh => false,
            Search::Hint(s) | Search::Frozen(s) => s.get(k).is_some_and(|s| s.repeated),
        }
    }

    /// Previous partner and parameter of slot k, and whether it must be kept.
    pub fn previous(&self, k: usize) -> Option<(Partner, [f64; 2], bool)> {
        match self {
            Search::Fresh => None,
            Search::Hint(s) => s.get(k).map(|s| (s.partner, s.xi, false)),
            Search::Frozen(s) => s.get(k).map(|s| (s.partner, s.xi, true)),
        }
    }
}

/// The state a formulation is evaluated at.
pub struct Ctx<'a> {
    pub model: &'a Model,
    /// The nodes' positions, location codes and the multipliers, as the assembler hands them.
    pub nodes: NodalState<'a>,
    pub dim: usize,
    pub laws: &'a Laws,
}

impl Ctx<'_> {
    /// A node's position at the last converged step (its reference position without one).
    pub fn start_position(&self, n: usize) -> [f64; 3] {
        self.nodes.start_position(n)
    }

    /// Current position of a node and the location codes of its displacement DOFs.
    pub fn position(&self, n: usize) -> Result<([f64; 3], [usize; 3])> {
        self.nodes.position(n)
    }
}

/// The local unknowns of one contact point: the positions of its nodes.
pub struct Local {
    pub nodes: Vec<usize>,
    pub codes: Vec<usize>,
    vals: Vec<f64>,
    pub(super) dim: usize,
}

impl Local {
    pub fn new(dim: usize) -> Local {
        Local {
            nodes: Vec::new(),
            codes: Vec::new(),
            vals: Vec::new(),
            dim,
        }
    }

    /// Add a node (once); returns its local index.
    pub fn add(&mut self, ctx: &Ctx, n: usize) -> Result<usize> {
        if let Some(k) = self.nodes.iter().position(|&m| m == n) {
            return Ok(k);
        }
        let (x, codes) = ctx.position(n)?;
        self.nodes.push(n);
        self.codes.extend_from_slice(&codes[..self.dim]);
        self.vals.extend_from_slice(&x[..self.dim]);
        Ok(self.nodes.len() - 1)
    }

    pub fn index(&self, n: usize) -> usize {
        self.nodes
            .iter()
            .position(|&m| m == n)
            .expect("node added to the local unknowns")
    }

    /// Current positions of the local nodes, node after node.
    pub fn values(&self) -> &[f64] {
        &self.vals
    }

    /// Number of local displacement unknowns.
    pub fn m(&self) -> usize {
        self.vals.len()
    }

    /// This set with `other`'s nodes added, and where each of `other`'s unknowns lands in it.
    pub fn union(&self, other: &Local) -> (Local, Vec<usize>) {
        let mut out = Local {
            nodes: self.nodes.clone(),
            codes: self.codes.clone(),
            vals: self.vals.clone(),
            dim: self.dim,
        };
        let mut map = Vec::with_capacity(other.m());
        for (k, &n) in other.nodes.iter().enumerate() {
            let at = match out.nodes.iter().position(|&m| m == n) {
                Some(at) => at,
                None => {
                    let range = k * self.dim..(k + 1) * self.dim;
                    out.nodes.push(n);
                    out.codes.extend_from_slice(&other.codes[range.clone()]);
                    out.vals.extend_from_slice(&other.vals[range]);
                    out.nodes.len() - 1
                }
            };
            map.extend((0..self.dim).map(|i| at * self.dim + i));
        }
        (out, map)
    }

    /// The node positions as dual vectors (each coordinate an unknown).
    pub fn seed(&self) -> Vec<DVec> {
        let m = self.m();
        assert!(m <= dual::MAXV, "contact pair with {m} unknowns");
        let q = dual::seed(&self.vals, m);
        (0..self.nodes.len())
            .map(|k| {
                let mut v = [Dual::constant(0.0, m); 3];
                v[..self.dim].copy_from_slice(&q[k * self.dim..(k + 1) * self.dim]);
                v
            })
            .collect()
    }

    /// B = Σ_k c_k n placed at node k's unknowns, for coefficients per local node.
    pub fn distribute(&self, coeffs: &[(usize, Dual)], n: &DVec) -> Vec<Dual> {
        let m = self.m();
        let mut b = vec![Dual::constant(0.0, m); m];
        for &(k, c) in coeffs {
            for i in 0..self.dim {
                b[k * self.dim + i] = b[k * self.dim + i] + c * n[i];
            }
        }
        b
    }

    /// [`Local::distribute`] as jets over the local unknowns.
    pub fn distribute_jets(&self, coeffs: &[(usize, Dual)], n: &DVec) -> Vec<dual::Jet> {
        self.distribute(coeffs, n)
            .into_iter()
            .map(dual::Jet::from)
            .collect()
    }
}

/// A contact formulation (one condition of the input).
pub trait Formulation {
    /// Number of contact points (slots): one per contact node.
    fn n_slots(&self) -> usize;
    /// Lagrange multipliers it adds (numbered after all displacement equations).
    fn n_multipliers(&self) -> usize;
    /// Nodes that must carry displacement DOFs even without elements.
    fn nodes_needing_dofs(&self) -> Vec<usize>;
    /// The nodes whose DOFs its contributions can touch from the state `ctx` on, as far as
    /// the geometry tells (the contact nodes, and the master nodes near them).
    fn candidate_nodes(&self, ctx: &Ctx) -> Result<Vec<usize>>;
    /// Whether its tangent is symmetric (B = ∇g at every contact point).
    fn symmetric(&self) -> bool;
    /// Its condition's number and the smallest and largest penalty in effect at its slots, if
    /// it is a penalty condition (for messages: a penalty from the mesh differs per slot).
    fn penalties(&self) -> Option<(usize, f64, f64)>;
    /// Take each contact node's penalty from the mesh as `stiffness[node]` (a force per
    /// displacement) where the condition gives none: explicit dynamics, whose stable step a
    /// penalty far stiffer than the node's own stiffness would shorten. None by default (the
    /// rule of [`crate::contact::law::penalty::from_mesh`] stays).
    fn set_mesh_penalties(&mut self, _stiffness: &[f64]) {}
    /// The master nodes of a partner (an edge's or a face's nodes; none for others).
    fn partner_nodes(&self, _partner: Partner) -> &[usize] {
        &[]
    }
    /// The rows (node k, node l, T_kl) of the slave nodes' basis transformation T whose
    /// multipliers are biorthogonal to modified shape functions N̂ = T N (mortar on quadratic
    /// faces): multiplier j acts on the slave nodes n with (T⁻¹)_nj, so its force is its own
    /// node's alone only in the equilibrium rows combined by T (row k ← Σ_l T_kl row l), where
    /// `solve::multipliers` eliminates it. Rows not listed are the identity's; none by default.
    fn slave_transform(&self) -> Vec<(usize, usize, f64)> {
        Vec::new()
    }
    /// Evaluate every slot at `ctx`; `first_lambda` is the equation of its first multiplier,
    /// `history` the converged states of the last step (the friction history), if any.
    /// Returns the seconds spent searching partners.
    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        search: Search,
        history: Option<&[SlotState]>,
        points: &mut Vec<SlotLinearization>,
        states: &mut Vec<SlotState>,
    ) -> Result<f64>;
}

/// The weights (w_s, w_m) of the slave's and the master's reference normals in the contact
/// normal of small deformation, ν = w_s ν_s + w_m ν_m normalized, for a slave element and a
/// master element: each body's compliance c = (1 − ν²)/E goes to the other's normal,
/// (w_s, w_m) = (c_m, c_s)/(c_s + c_m).
///
/// Pressed together, two bodies meet on a surface between their reference surfaces, each
/// displaced in proportion to its compliance (Hertz): its normal is this blend to first order —
/// the mean of the two for equal bodies, the stiffer body's for a rigid one. Traction along one
/// body's reference normal alone is off by the angle between the two (a/R at a Hertz contact's
/// rim), a shear of that order on the interface: two equal spheres pressed together, which by
/// symmetry meet on a plane, gave 0.7 % less force and 0.7–1.3 % more pressure than one sphere
/// on a rigid plane. In large deformation the current surfaces coincide where they touch and
/// the slave's current normal is used instead. Equal weights when a modulus is not positive.
pub fn interface_weights(model: &Model, slave_element: usize, master_element: usize) -> (f64, f64) {
    let compliance = |e: usize| {
        let mat = &model.materials[model.elements[e].material];
        let (young, nu) = (mat.young(), mat.poisson());
        (young > 0.0 && young.is_finite()).then(|| (1.0 - nu * nu) / young)
    };
    match (compliance(slave_element), compliance(master_element)) {
        (Some(cs), Some(cm)) if cs + cm > 0.0 => (cm / (cs + cm), cs / (cs + cm)),
        _ => (0.5, 0.5),
    }
}

/// The modulus of friction's c_T at a slave node of modulus `slave` against a master of modulus
/// `master`: the two in series, E_s E_m / (E_s + E_m), as the tangential compliance of the
/// contact is the sum of the two bodies'. With the slave's alone, c_T of a stiff slave on a
/// soft master (the shallow ironing's die, ten times the block's E) is ten times the contact's
/// stiffness, and the stick/slip iteration cycled at nodes on the stick–slip boundary.
pub fn friction_modulus(slave: f64, master: f64) -> f64 {
    if master.is_infinite() || !(master > 0.0) {
        slave
    } else {
        slave * master / (slave + master)
    }
}
/// The area a contact node stands for in the laws: its tributary area, or for a node on no
/// contact surface (an isolated node) that of a tenth of the model's size.
pub fn law_area(tributary: f64, model: &Model) -> f64 {
    if tributary > 0.0 {
        tributary
    } else {
        (0.1 * model_size(model)).powi(model.domain.nsd() as i32 - 1)
    }
}

/// Apply a condition's law to the kinematics of one contact point and complete its state.
/// `lambda_eqs`: the equations of the point's multipliers (the friction force's components, if
/// any, then the normal force).
pub fn apply_law(
    ctx: &Ctx,
    law: law::SlotLaw,
    lambda_eqs: Option<std::ops::Range<usize>>,
    local: &Local,
    kin: &law::SlotKinematics,
    area: f64,
    state: &mut SlotState,
) -> SlotLinearization {
    let codes = local.codes.clone();
    let multipliers = law.is_multipliers();
    let free = |c| ctx.nodes.is_free(c);
    let forces = lambda_eqs.map(|eqs| law::Forces {
        values: ctx.nodes.multipliers(eqs.clone()),
        eqs,
        // A penalty with its forces as unknowns: its compliance 1/ε.
        compliance: law.compliance(),
        free: &free,
    });
    let forces_known = forces.is_none();
    let (point, friction) = law.evaluate(ctx.laws, codes, forces, kin);
    if let Some(s) = kin.slip.as_ref().filter(|_| !forces_known) {
        state.friction = friction;
        // A sticking node keeps its anchor; a sliding one leaves it behind by its elastic slip
        // (none without a penalty: where it is now, as an open one, the state's anchor from
        // the kinematics).
        match friction {
            Some((true, _)) => state.anchor = Some(s.kept),
            Some((false, _)) if s.slid.is_some() => state.anchor = s.slid,
            _ => {}
        }
    }
    let penalty = if forces_known { law.penalty() } else { 0.0 };
    state.force = law::normal_force(&point, kin, penalty);
    state.area = area;
    state.active = point.closed && (multipliers || kin.gap.v < 0.0);
    state.pressure = if area > 0.0 {
        state.force / area
    } else {
        f64::NAN
    };
    point
}

/// The condition `number`'s smallest and largest penalty over `laws`, if they are penalties.
pub fn penalty_range(
    number: usize,
    laws: impl Iterator<Item = law::SlotLaw>,
) -> Option<(usize, f64, f64)> {
    let p: Vec<f64> = laws
        .filter(|l| !l.is_multipliers())
        .map(|l| l.penalty())
        .collect();
    (!p.is_empty()).then(|| {
        let lo = p.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = p.iter().copied().fold(0.0, f64::max);
        (number, lo, hi)
    })
}
