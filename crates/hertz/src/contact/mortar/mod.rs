//! Mortar segment-to-segment contact: the non-penetration condition is imposed in a weak sense
//! along the slave surface, one constraint per slave node, so that a contact pressure is
//! transferred between non-matching meshes exactly (the contact patch test).
//!
//! Glossary (one slave node j with shape function N_j on the slave surface and dual shape
//! function Φ_j, biorthogonal to the N_k on each slave face of the reference configuration, in
//! 2D on the part of each slave edge that overlaps the master: ∫ Φ_j N_k = δ_jk ∫ N_k,
//! Σ_j Φ_j = 1):
//! * weighted gap g̃_j = ∫ Φ_j g dA, support D_j = ∫ N_j dA over the parts of the slave surface
//!   that overlap the master, mean gap ḡ_j = g̃_j / D_j (g < 0: penetration);
//! * force direction B_j: the slave node k gets ∫ Φ_j N_k ν dA, the master node l −∫ Φ_j M_l ν dA
//!   (ν towards the slave body; the variation of g̃_j at fixed segmentation and normal) for the
//!   penalty; for multipliers w_jn n̂_j along the node's normal (`SlipForm::along_normal`), so
//!   that each slave node carries its own multiplier alone and the multipliers condense out.
//!
//! The laws act on ḡ_j along B_j with a pressure λ_j: the penalty λ_j = −ε ḡ_j (ε a penalty per
//! unit area), the multipliers λ_j with ḡ_j = 0 while active. A uniform pressure p gives λ_j = p
//! at every slave node, whose forces Σ_j λ_j B_j are then exactly the consistent nodal forces of p
//! on both meshes (Σ_j Φ_j = 1): the patch test holds to round-off. With the dual basis a slave
//! node's force is its own multiplier times its support, not spread over its neighbours.
//!
//! Coulomb friction acts on each slave node's weighted slip in a step (`SlipForm`; the shares
//! of the reference segmentation in small deformation, of the current one in large), with the
//! friction multipliers of [`law::multiplier`] (with a penalty, its compliance in their rows), as
//! node-to-segment friction does, so that a uniform shear traction is transferred exactly as
//! well.
//!
//! [`edges`]: 2D, straight and quadratic edges, against edges or rigid shapes; [`faces`]: 3D,
//! triangle and quadrilateral faces against faces (segmented by [`segment`]) or rigid planes and
//! spheres.

pub mod curved;
pub mod edges;
mod face_terms;
pub mod faces;
pub mod mirror;
mod own;
pub mod segment;

use super::dual::Jet;
use super::formulation::{self, Anchor, Ctx, Formulation, Local, Partner, SlotState};
use super::law::{self, Laws, SlipKinematics, SlotFriction, SlotKinematics, SlotLaw};
use super::slot::SlotLinearization;
use crate::error::Result;
use crate::model::queries::{master_young, stiffest_young};
use crate::model::{Enforcement, Friction, Model, SegmentKind};

/// The formulation of mortar condition `ci`: edges in 2D, faces in 3D.
pub fn new(model: &Model, ci: usize) -> Result<Box<dyn Formulation + Send + Sync>> {
    if model.domain.nsd() == 3 {
        Ok(Box::new(faces::FaceMortar::new(model, ci)?))
    } else {
        Ok(Box::new(edges::Mortar::new(model, ci)?))
    }
}

/// The size of a problem's contact surfaces: 4 × the diagonal of the box around `nodes` in the
/// reference configuration (the search for a partner gives up beyond it).
fn search_limit(model: &Model, nodes: impl Iterator<Item = usize>) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for n in nodes {
        let x = model.nodes[n].coords;
        for i in 0..3 {
            lo[i] = lo[i].min(x[i]);
            hi[i] = hi[i].max(x[i]);
        }
    }
    4.0 * (0..3).map(|i| (hi[i] - lo[i]).powi(2)).sum::<f64>().sqrt()
}

/// The node a rigid segment moves with.
fn rigid_node(model: &Model, g: usize) -> Option<usize> {
    match &model.segments[g].kind {
        SegmentKind::Circle { node, .. } | SegmentKind::Plane { node, .. } => *node,
        _ => None,
    }
}

/// A master facet that can overlap a slave facet: its index, its distance from the slave facet
/// along the slave's outward normal (< 0: behind it) and its size.
#[derive(Debug, Clone, Copy)]
struct Facing {
    index: usize,
    dist: f64,
    size: f64,
}

/// A master edge or face faces a slave one when their outward normals make more than 90.6°
/// (n_m·n_s below this), not merely more than 90°. Perpendicular to within that, the slave's
/// normal rays graze the master: the side edge of a slave surface's corner (a hairpin arm's tip
/// face, 0.02° off perpendicular) overlapped master edges far along them for 1e-5 of its
/// length, gaps of ±1.5 that closed and opened its corner node by turns.
pub(super) const GRAZING: f64 = -0.01;

/// The master facets of the sheet nearest to a slave facet of size `size`, among the facing,
/// overlapping ones that `query(grow)` finds in the slave facet's box grown by `grow`: the box
/// grows (up to `limit`, the problem's size) until it holds the nearest facet and the rest of its
/// sheet (those within a facet size of its distance), so that a facet finds its partners at any
/// gap — in small deformation the reference segmentation is final — while a farther sheet (the
/// other side of a thin body) is left out.
fn nearest_sheet(
    size: f64,
    limit: f64,
    mut query: impl FnMut(f64) -> Result<Vec<Facing>>,
) -> Result<Vec<usize>> {
    let mut grow = size;
    loop {
        let found = query(grow)?;
        let nearest = found
            .iter()
            .min_by(|a, b| a.dist.abs().total_cmp(&b.dist.abs()));
        if let Some(best) = nearest {
            let tol = |f: &Facing| size.max(f.size).max(best.size);
            if best.dist.abs() + 2.0 * tol(best) <= grow || grow >= limit {
                return Ok(found
                    .iter()
                    .filter(|f| (f.dist - best.dist).abs() <= tol(f))
                    .map(|f| f.index)
                    .collect());
            }
        } else if grow >= limit {
            return Ok(Vec::new());
        }
        grow *= 2.0;
    }
}

/// A mortar slot's friction anchor on `partner`, keeping the elastic slip `elastic` of the last
/// converged step (none with multipliers; a mortar slip is weighted over the slot's support:
/// no point on the partner).
fn anchor_on(partner: Partner, elastic: [f64; 3]) -> Anchor {
    Anchor {
        partner,
        xi: [0.0; 2],
        offset: elastic,
    }
}

/// What one slave node's constraint integrates to, over its local unknowns.
struct Weighted {
    /// g̃_j.
    gap: Jet,
    /// D_j.
    area: Jet,
    /// B_j.
    b: Vec<Jet>,
    partner: Partner,
    /// The shares of the weighted slip, for friction.
    slip: Option<SlipForm>,
}

/// Whether the force direction `kin.b` on `node` itself lies along held unknowns (a force along
/// its own held motion) and on every master node (not in `slave`) too: the constraint then
/// moves nothing that is free but the slave neighbours' round-off shares. A master that moves
/// (a body pushed onto a held slave surface) keeps the constraint: it holds that body.
fn held_along_force(
    ctx: &Ctx,
    local: &Local,
    node: usize,
    kin: &SlotKinematics,
    slave: &std::collections::HashSet<usize>,
) -> bool {
    let dim = local.dim;
    let entries = |n: usize| {
        let k = local.index(n);
        (0..dim).map(move |i| (kin.b[dim * k + i].v, local.codes[dim * k + i]))
    };
    let size = entries(node).fold(0.0, |a: f64, (v, _)| a.max(v.abs()));
    let held =
        |n: usize| entries(n).all(|(v, code)| v.abs() <= 1e-9 * size || !ctx.nodes.is_free(code));
    size > 0.0
        && held(node)
        && (local.nodes.iter())
            .filter(|n| !slave.contains(n))
            .all(|&n| held(n))
}

impl Weighted {
    /// No support: a slot that holds nothing (its multiplier at zero).
    fn none(m: usize) -> Weighted {
        Weighted {
            gap: Jet::constant(0.0, m),
            area: Jet::constant(0.0, m),
            b: vec![Jet::constant(0.0, m); m],
            partner: Partner::None,
            slip: None,
        }
    }
}

/// A slave node's weighted slip in a step, ũ_j = Σ_n w_jn·(x_n − x⁰_n) / D_j, x⁰ the positions
/// of the last converged step, with the shares w_jn = ∫ Φ_j N_n dA for slave nodes and
/// −∫ Φ_j M_l dA for master nodes (of the reference segmentation in small deformation, of the
/// current one in large). They sum to zero, so ũ_j vanishes when both bodies translate
/// together: it is the mean relative motion of the slave over the master under node j's weight
/// in the step, and a traction t at the node does the virtual work Σ_n w_jn t·δx_n.
#[derive(Debug, Clone)]
struct SlipForm {
    /// (local node index, w_jn over the local unknowns).
    shares: Vec<(usize, Jet)>,
    /// ∫ Φ_j ν dA: the direction of the normal (over the local unknowns: against a rigid shape
    /// ν is the shape's normal at the current point).
    normal: [Jet; 3],
}

/// The law of a mortar condition at each of its slots.
struct MortarLaw {
    number: usize,
    enforcement: Enforcement,
    /// Coulomb friction.
    friction: Option<Friction>,
    /// Per slot, the condition's law there (a penalty per unit area, given or from the mesh)
    /// and its friction.
    laws: Vec<SlotLaw>,
    frictions: Vec<Option<SlotFriction>>,
    /// Per slot, E/h (E of the stiffest element at the node and the master's in series, see
    /// [`super::friction_modulus`]; h the size of its slave facets): the friction multipliers'
    /// c_T, per unit area.
    stiffness: Vec<f64>,
    /// Per slot, the support the node would have if the master covered all its slave facets
    /// (reference facets, straight edges and flat faces), and the penalty per unit area from the
    /// mesh: the multipliers fade to it on the last slivers of a master's end (see
    /// [`MortarLaw::sliver_compliance`]).
    full_support: Vec<f64>,
    mesh_penalty: Vec<f64>,
    dim: usize,
    /// The slave nodes (the slots), unless the condition is self-contact (its slave surface is
    /// among its masters): see [`held_along_force`].
    slave_nodes: Option<std::collections::HashSet<usize>>,
}

/// The share of its full support below which a slave node's multiplier fades into a penalty
/// (see [`MortarLaw::sliver_compliance`]).
const SLIVER: f64 = 0.2;

/// The share of its full support below which a slot's support is the round-off of its overlaps
/// and it has none: a strip along an edge two faces share, its width the round-off of carried
/// corners. Its gap g̃/D is then noise (a tube's crease tips, translated 1 000 spacings, closed
/// on ḡ = −0.04 over supports of 1e-23 and the residual rose to 1e16), and the force it could
/// carry, ε(D)·D·ḡ with the sliver's fading penalty, is of the order of the share squared.
const NO_SUPPORT: f64 = 1e-9;

impl MortarLaw {
    /// The law at every slot (slave nodes `slots`): a penalty per unit area given, or from the
    /// mesh ([`law::penalty::from_mesh`], h = `size` the size of its slave facets); `full_support`
    /// per slot as in [`MortarLaw::full_support`].
    fn new(
        model: &Model,
        ci: usize,
        slots: &[usize],
        size: impl Fn(usize) -> f64,
        full_support: Vec<f64>,
    ) -> MortarLaw {
        let c = &model.contacts[ci];
        let young = stiffest_young(model);
        let stiffest = young.values().copied().fold(0.0, f64::max);
        // The slave's modulus at each slot, and the master's (friction's c_T has both).
        let slave: Vec<f64> = slots
            .iter()
            .map(|n| young.get(n).copied().unwrap_or(stiffest))
            .collect();
        let master = match &c.pairing {
            crate::model::Pairing::Mortar { segments, .. } => master_young(model, segments),
            _ => f64::INFINITY,
        };
        let mesh_penalty: Vec<f64> = (0..slots.len())
            .map(|j| {
                let factor = law::penalty::mesh_factor(model);
                law::penalty::from_mesh(slave[j], master, 1.0 / size(j), factor)
            })
            .collect();
        let laws: Vec<SlotLaw> = mesh_penalty
            .iter()
            .map(|&mesh| SlotLaw::resolve(c.enforcement, mesh, 1.0))
            .collect();
        let frictions = laws
            .iter()
            .map(|l| c.friction.map(|f| l.friction(f, 1.0)))
            .collect();
        let stiffness = (0..slots.len())
            .map(|j| formulation::friction_modulus(slave[j], master) / size(j))
            .collect();
        MortarLaw {
            number: c.number,
            enforcement: c.enforcement,
            friction: c.friction,
            laws,
            frictions,
            stiffness,
            full_support,
            mesh_penalty,
            dim: model.domain.nsd(),
            slave_nodes: match &c.pairing {
                crate::model::Pairing::Mortar { slave, segments } if segments.contains(slave) => {
                    None
                }
                _ => Some(slots.iter().copied().collect()),
            },
        }
    }

    /// Whether slot `j` with support `area` has any ([`NO_SUPPORT`]).
    fn has_support(&self, j: usize, area: f64) -> bool {
        area > NO_SUPPORT * self.full_support[j]
    }

    /// 1/ε_j(D_j) of a multiplier slot whose support D_j (`area`, over the local unknowns) is
    /// below [`SLIVER`] of its full support S_j: ε_j(D) = ε_mesh·r/(ρ − r), r = D/S, ρ = SLIVER,
    /// infinite (the exact constraint, compliance 0) from r = ρ on and falling to zero with D.
    ///
    /// Where a slave node's facets slide off a master's end, its support is the sliver the master
    /// still covers. Held to ḡ_j = 0 there (ḡ_j is then the gap extrapolated to the node), the
    /// node keeps a finite force λ_j·D_j as D_j → 0 and drops it at once when the master's end
    /// passes its neighbour: a node the force pushes off has no solution, and Newton chatters
    /// between the two states (a rubber block's corner bulging past a die as wide as it). A penalty
    /// has none of this — its force ε·D·(−ḡ) falls with the sliver — so the multiplier does as
    /// the penalty does there, with a penalty that falls as well, and the node lets go
    /// continuously. Nodes with at least ρ of their support on the master keep the exact
    /// constraint, so the patch tests and every fully covered node are untouched.
    fn sliver_compliance(&self, j: usize, area: &Jet) -> Option<Jet> {
        let s = self.full_support[j];
        let r = area.v / s;
        if !(r > 0.0 && r < SLIVER) {
            return None;
        }
        let eps = self.mesh_penalty[j];
        // (ρ/r − 1)/ε with ∂ = −ρ/(ε r²)·∂D/S.
        let slope = -SLIVER / (eps * r * r * s);
        Some(Jet {
            v: (SLIVER / r - 1.0) / eps,
            d: area.d.iter().map(|d| slope * d).collect(),
        })
    }

    /// Whether the law keeps a tangent with B = ∇g̃ symmetric: the penalty's ε B ⊗ ∇ḡ is
    /// ε B ⊗ B / D_j; a multiplier's row is ḡ_j = g̃_j / D_j while its force is λ_j B_j, so
    /// K_λu = K_uλᵀ / D_j (the full tangent stored as one triangle lost the other: mortar
    /// multipliers solved with full tangents diverged).
    fn symmetric(&self) -> bool {
        !self.enforcement.forces_are_unknowns(self.friction)
    }

    /// The condition's smallest and largest penalty in effect (see
    /// [`super::Formulation::penalties`]).
    fn penalties(&self) -> Option<(usize, f64, f64)> {
        formulation::penalty_range(self.number, self.laws.iter().copied())
    }

    fn n_multipliers(&self, slots: usize) -> usize {
        if self.enforcement.forces_are_unknowns(self.friction) {
            slots * self.multipliers_per_slot()
        } else {
            0
        }
    }

    /// Multipliers per slave node: the pressure's, and with friction the friction traction's
    /// components.
    fn multipliers_per_slot(&self) -> usize {
        1 + if self.friction.is_some() { self.dim } else { 0 }
    }

    /// The contact point and state of slot `j` (slave node `node`) from its integrals, with the
    /// friction anchored where `history` (the converged states of the last step) leaves it, if
    /// the condition has friction. `merged`: the kinematics (over their own unknowns) of a
    /// self-contact pair's one constraint ([`crate::contact::repeated`]) in place of the slot's.
    #[allow(clippy::too_many_arguments)]
    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        j: usize,
        node: usize,
        local: &Local,
        mut w: Weighted,
        history: Option<&[SlotState]>,
        merged: Option<(Local, SlotKinematics)>,
    ) -> Result<(SlotLinearization, SlotState)> {
        let mut state = SlotState {
            partner: w.partner,
            xi: [0.0; 2],
            ..SlotState::unpaired(self.number, node, ctx.position(node)?.0)
        };
        let b = std::mem::take(&mut w.b);
        let (merged_local, mut kin) = match merged {
            Some((l, k)) => (Some(l), k),
            None => (None, self.slot_kinematics(j, local, &w, b)),
        };
        let local = merged_local.as_ref().unwrap_or(local);
        // A node held along its own force (a half model's slave node on its symmetry plane, a
        // node held on the plane it meets): the supports take that force, and the constraint
        // repeats the support's but for a round-off share of the neighbours' gaps (the dual
        // basis is biorthogonal in the reference configuration), which left its multiplier
        // undetermined: a hollow torus's half model chattered on its two cut nodes. It holds
        // nothing.
        let held = merged_local.is_none()
            && (self.slave_nodes.as_ref())
                .is_some_and(|s| held_along_force(ctx, local, node, &kin, s));
        let has = self.has_support(j, w.area.v) && !held;
        // Its gap is still reported.
        let held_gap = held.then_some(kin.gap.v);
        if held {
            kin = self.slot_kinematics(j, local, &Weighted::none(local.m()), Vec::new());
        }
        // The multipliers' active-set rule compares a pressure with c·ḡ: c per unit area.
        let laws = Laws {
            c: ctx.laws.c / w.area.v.max(1e-300),
            ..*ctx.laws
        };
        let codes = local.codes.clone();
        let penalty = self.laws[j].penalty();
        let multipliers = self.enforcement.forces_are_unknowns(self.friction);
        // A penalty with its forces as unknowns: its compliance 1/ε (see `law::multiplier`);
        // multipliers on a sliver of a master's end fade into a penalty.
        let sliver = (has && self.laws[j].is_multipliers())
            .then(|| self.sliver_compliance(j, &w.area))
            .flatten();
        let penalty_form = multipliers && penalty > 0.0;
        let compliance = if penalty_form {
            1.0 / penalty
        } else {
            sliver.as_ref().map_or(0.0, |c| c.v)
        };
        if self.frictions[j].is_some() && has {
            // A repeated pair's merged kinematics carry the pair's slip already.
            if kin.slip.is_none() {
                kin.slip = self.slip_kinematics(ctx, j, local, &w, history);
            }
            // Open (or without a penalty): no elastic slip left.
            if kin.slip.is_some() {
                state.anchor = Some(anchor_on(w.partner, [0.0; 3]));
            }
        }
        let point = if multipliers {
            let per = self.multipliers_per_slot();
            let eqs = first_lambda + per * j..first_lambda + per * (j + 1);
            let lambdas = ctx.nodes.multipliers(eqs.clone());
            if let Some(c) = &sliver {
                // The row ḡ + c(q)·λ: the law takes c's value, its variation rides on ḡ's.
                let lambda = lambdas[per - 1];
                for (g, d) in kin.gap.d.iter_mut().zip(&c.d) {
                    *g += lambda * d;
                }
            }
            let free = |c| ctx.nodes.is_free(c);
            let forces = law::Forces {
                eqs,
                values: lambdas,
                compliance,
                free: &free,
            };
            let (point, friction) = self.laws[j].evaluate(&laws, codes, Some(forces), &kin);
            if let Some(s) = &kin.slip {
                // Traction per unit area: the node's force is its times D_j.
                state.friction = friction.map(|(stick, t)| (stick, t * w.area.v));
                // A closed penalty slot leaves its elastic slip λ_T/ε_T.
                if friction.is_some() && s.compliance > 0.0 {
                    state.anchor = Some(anchor_on(
                        w.partner,
                        std::array::from_fn(|i| {
                            if i < self.dim {
                                lambdas[i] * s.compliance
                            } else {
                                0.0
                            }
                        }),
                    ));
                }
            }
            point
        } else {
            self.laws[j].evaluate(&laws, codes, None, &kin).0
        };
        if has {
            self.record_force(j, &point, &kin, &w, &mut state);
        } else if let Some(gap) = held_gap {
            state.gap = gap;
        } else {
            state.partner = Partner::None;
        }
        Ok((point, state))
    }

    /// The friction kinematics of slot `j` (with friction and support) from its integrals `w`:
    /// its weighted slip in the step, with a penalty from its anchor's elastic slip (`history`:
    /// the last converged states).
    fn slip_kinematics(
        &self,
        ctx: &Ctx,
        j: usize,
        local: &Local,
        w: &Weighted,
        history: Option<&[SlotState]>,
    ) -> Option<SlipKinematics> {
        let (f, slip) = (self.frictions[j]?, w.slip.as_ref()?);
        let penalty_form =
            self.enforcement.forces_are_unknowns(self.friction) && self.laws[j].penalty() > 0.0;
        let anchor = history
            .and_then(|h| h.get(j))
            .and_then(|s| s.anchor.as_ref());
        let elastic = match anchor {
            Some(a) if penalty_form => a.offset,
            _ => [0.0; 3],
        };
        let u = slip.slip(ctx, local, &w.area, elastic);
        let mut sk = slip.kinematics(
            local,
            u,
            anchor_on(w.partner, elastic),
            f.mu,
            self.stiffness[j],
        );
        if penalty_form {
            sk.compliance = 1.0 / f.penalty;
        }
        Some(sk)
    }

    /// The kinematics of slot `j` from its integrals `w`: the weighted gap ḡ = g̃ / D with its
    /// gradient, the force direction (with multipliers along the node's normal, see
    /// `SlipForm::along_normal`, so that it condenses out exactly); none without support.
    fn slot_kinematics(
        &self,
        j: usize,
        local: &Local,
        w: &Weighted,
        b: Vec<Jet>,
    ) -> SlotKinematics {
        let m = local.m();
        let has = self.has_support(j, w.area.v);
        let (gap, b) = if has {
            let q = w.gap.v / w.area.v;
            let d = (w.gap.d.iter().zip(&w.area.d))
                .map(|(a, b)| (a - q * b) / w.area.v)
                .collect();
            let b = match &w.slip {
                Some(slip) if self.laws[j].is_multipliers() => slip.along_normal(local),
                _ => b,
            };
            (Jet { v: q, d }, b)
        } else {
            (Jet::constant(f64::NAN, m), vec![Jet::constant(0.0, m); m])
        };
        SlotKinematics {
            gap,
            weight: Jet::constant(if has { 1.0 } else { 0.0 }, m),
            b,
            area: 1.0,
            past_end: None,
            slip: None,
        }
    }

    /// The gap, pressure and force of slot `j` with support into its `state`. The slot's force
    /// on the slave body: λ ∫ Φ_j ν along B for a penalty, whose size |∫ Φ_j ν| is below D_j
    /// where the slave's facets turn (a curved die: 1.4 % on the shallow ironing's arc), and
    /// λ D_j along the node's normal for multipliers.
    fn record_force(
        &self,
        j: usize,
        point: &SlotLinearization,
        kin: &SlotKinematics,
        w: &Weighted,
        state: &mut SlotState,
    ) {
        state.gap = kin.gap.v;
        let lambda = law::normal_force(point, kin, self.laws[j].penalty());
        state.pressure = lambda;
        let support = match &w.slip {
            Some(s) if !self.laws[j].is_multipliers() => {
                s.normal.iter().map(|n| n.v * n.v).sum::<f64>().sqrt()
            }
            _ => w.area.v,
        };
        state.force = lambda * support;
        state.area = support;
        state.active = point.closed && (self.laws[j].is_multipliers() || kin.gap.v < 0.0);
    }
}

impl SlipForm {
    /// The share of local node `k` (over the local unknowns), zero where it has none yet.
    fn share_mut(&mut self, k: usize) -> &mut Jet {
        let at = match self.shares.iter().position(|s| s.0 == k) {
            Some(at) => at,
            None => {
                let m = self.normal[0].d.len();
                self.shares.push((k, Jet::constant(0.0, m)));
                self.shares.len() - 1
            }
        };
        &mut self.shares[at].1
    }

    /// The force direction of a multiplier: node n gets w_jn n̂_j, n̂_j = ∫ Φ_j ν / |∫ Φ_j ν| (over
    /// the local unknowns). With the dual basis w_jk = δ_jk D_j among the slave nodes wherever the
    /// master covers the slave facets, so a slave node carries its own multiplier alone and the
    /// multipliers are eliminated through the slave rows (`solve::multipliers`) even where ν
    /// varies over a facet (quadratic edges, rigid shapes), where ∫ Φ_j N_k ν would reach the
    /// neighbours. A uniform pressure still gives the consistent nodal forces on a flat surface.
    fn along_normal(&self, local: &Local) -> Vec<Jet> {
        let (dim, m) = (local.dim, local.m());
        let len = (0..dim)
            .map(|i| self.normal[i].v * self.normal[i].v)
            .sum::<f64>()
            .sqrt();
        // n̂ with ∂n̂ = (∂ν − n̂ (n̂·∂ν)) / |ν|.
        let unit: Vec<Jet> = (0..dim)
            .map(|i| {
                let v = self.normal[i].v / len;
                let d = (0..m)
                    .map(|t| {
                        let proj: f64 = (0..dim)
                            .map(|k| self.normal[k].v * self.normal[k].d[t])
                            .sum::<f64>()
                            / len;
                        (self.normal[i].d[t] - v * proj) / len
                    })
                    .collect();
                Jet { v, d }
            })
            .collect();
        let mut b = vec![Jet::constant(0.0, m); m];
        for (k, w) in &self.shares {
            for (i, u) in unit.iter().enumerate() {
                b[dim * k + i] = w.product(u);
            }
        }
        b
    }

    /// `elastic` (the elastic slip the last converged step left) plus the step's slip ũ_j, over
    /// the local unknowns (D_j = `area`).
    fn slip(&self, ctx: &Ctx, local: &Local, area: &Jet, elastic: [f64; 3]) -> Vec<Jet> {
        let (dim, m) = (local.dim, local.m());
        let mut out: Vec<Jet> = (0..dim).map(|i| Jet::constant(elastic[i], m)).collect();
        let d = area.v;
        for (k, w) in &self.shares {
            let x0 = ctx.start_position(local.nodes[*k]);
            for (i, s) in out.iter_mut().enumerate() {
                let du = local.values()[dim * k + i] - x0[i];
                s.v += w.v * du / d;
                // ∂(w du / D) = du (∂w/D − w ∂D/D²) + w/D ∂du.
                for ((sd, wd), ad) in s.d.iter_mut().zip(&w.d).zip(&area.d) {
                    *sd += du * (wd / d - w.v * ad / (d * d));
                }
                s.d[dim * k + i] += w.v / d;
            }
        }
        out
    }

    /// What the friction multipliers of the slot need (see [`law::multiplier`]): the step's slip
    /// `slip`, the normal ∫ Φ_j ν, a unit traction's residual (w_jn on node n's component).
    fn kinematics(
        &self,
        local: &Local,
        slip: Vec<Jet>,
        kept: Anchor,
        mu: f64,
        stiffness: f64,
    ) -> SlipKinematics {
        let (dim, m) = (local.dim, local.m());
        let mut share = vec![vec![Jet::constant(0.0, m); m]; dim];
        for (k, w) in &self.shares {
            for (i, row) in share.iter_mut().enumerate() {
                row[dim * k + i] = w.clone();
            }
        }
        SlipKinematics {
            slip,
            normal: self.normal[..dim].to_vec(),
            share,
            mu,
            stiffness,
            kept,
            compliance: 0.0,
            slid: None,
        }
    }
}
