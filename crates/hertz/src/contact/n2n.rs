//! Node-to-node contact (spec §2.2, §2.3): fixed (master, slave) pairs with a fixed normal n (the
//! prescribed `normal`, or the initial master-to-slave direction); g = (x_s − x_m)·n, B = [n; −n].
//! The tangent is symmetric (B = ∇g) and, for the penalty, constant while closed.

use super::dual::{self, Dual};
use super::formulation::{self, apply_law, Ctx, Formulation, Local, Partner, Search, SlotState};
use super::law::{SlotKinematics, SlotLaw};
use super::slot::SlotLinearization;
use super::tributary::PressureAreas;
use crate::error::{Error, Result};
use crate::model::{Model, Pairing};

struct Pair {
    master: usize,
    slave: usize,
    normal: [f64; 3],
    area: f64,
}

pub struct NodeToNode {
    number: usize,
    /// Every pair's law (node-to-node conditions give their penalty: none from the mesh).
    law: SlotLaw,
    /// The pairs' forces are unknowns of the Newton system: multipliers, and a penalty outside
    /// explicit dynamics, solved with its compliance 1/ε in the rows (λ = −ε·g at the solution,
    /// the penalty's own; see `contact::law::multiplier`). With the force −ε·g of the iterate
    /// instead, a penalty far stiffer than the elements decided each pair's branch on gaps at the
    /// round-off of the solve: two 4 × 4 × 4 brick blocks pressed together by 25 pairs with
    /// ε = 1e12 (E = 1000) opened and closed a dozen pairs each iteration and failed after 3
    /// halvings; in this form 2 iterations.
    forces_unknown: bool,
    pairs: Vec<Pair>,
    /// The areas the slave nodes' pressures refer to.
    areas: PressureAreas,
}

impl NodeToNode {
    pub fn new(model: &Model, ci: usize) -> Result<NodeToNode> {
        let c = &model.contacts[ci];
        let Pairing::NodeToNode { pairs } = &c.pairing else {
            unreachable!("a node-to-node condition")
        };
        let err = |msg: String| Error::Input {
            span: c.span.clone(),
            msg,
        };
        let slaves: Vec<usize> = pairs.iter().map(|p| p.1).collect();
        let areas = super::tributary::tributaries(model, &slaves);
        let mut out = Vec::with_capacity(pairs.len());
        for (&(m, s), trib) in pairs.iter().zip(areas) {
            let label = |n: usize| model.nodes[n].label;
            if m == s {
                return Err(err(format!(
                    "node {} is paired with itself (it is in both the master and the slave set)",
                    label(m)
                )));
            }
            let normal = match c.normal {
                Some(n) => n,
                None => {
                    let (xm, xs) = (model.nodes[m].coords, model.nodes[s].coords);
                    let d = [xs[0] - xm[0], xs[1] - xm[1], xs[2] - xm[2]];
                    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    if len < 1e-8 {
                        return Err(err(format!(
                            "nodes {} and {} are too close to define a contact normal; give `normal`",
                            label(m),
                            label(s)
                        )));
                    }
                    [d[0] / len, d[1] / len, d[2] / len]
                }
            };
            out.push(Pair {
                master: m,
                slave: s,
                normal,
                area: trib.measure,
            });
        }
        let law = SlotLaw::resolve(c.enforcement, f64::NAN, 1.0);
        let explicit = model.analysis.kind == crate::model::AnalysisKind::NlDEIDynamic;
        Ok(NodeToNode {
            number: c.number,
            law,
            forces_unknown: law.is_multipliers() || !explicit,
            pairs: out,
            areas: PressureAreas::new(model, &slaves),
        })
    }
}

impl Formulation for NodeToNode {
    fn n_slots(&self) -> usize {
        self.pairs.len()
    }

    fn n_multipliers(&self) -> usize {
        if self.forces_unknown {
            self.pairs.len()
        } else {
            0
        }
    }

    fn nodes_needing_dofs(&self) -> Vec<usize> {
        self.pairs
            .iter()
            .flat_map(|p| [p.master, p.slave])
            .collect()
    }

    fn candidate_nodes(&self, _ctx: &Ctx) -> Result<Vec<usize>> {
        Ok(self.nodes_needing_dofs())
    }

    fn penalties(&self) -> Option<(usize, f64, f64)> {
        formulation::penalty_range(self.number, std::iter::once(self.law))
    }

    fn symmetric(&self) -> bool {
        true
    }

    fn evaluate(
        &self,
        ctx: &Ctx,
        first_lambda: usize,
        _search: Search,
        _history: Option<&[SlotState]>,
        points: &mut Vec<SlotLinearization>,
        states: &mut Vec<SlotState>,
    ) -> Result<f64> {
        let dim = ctx.dim;
        let areas = self.areas.at(|n| Ok(ctx.position(n)?.0))?;
        for (k, p) in self.pairs.iter().enumerate() {
            let mut local = Local::new(dim);
            local.add(ctx, p.slave)?;
            local.add(ctx, p.master)?;
            let x = local.seed();
            let n = dual::constant_vec(&p.normal[..dim], local.m());
            let gap = dual::dot(&dual::sub(&x[0], &x[1], dim), &n, dim);
            let m = local.m();
            let kin = SlotKinematics::from_duals(
                gap,
                Dual::constant(1.0, m),
                &local.distribute(
                    &[(0, Dual::constant(1.0, m)), (1, Dual::constant(-1.0, m))],
                    &n,
                ),
                formulation::law_area(p.area, ctx.model),
            );
            let lambda_eqs = self
                .forces_unknown
                .then_some(first_lambda + k..first_lambda + k + 1);
            let mut state = SlotState {
                partner: Partner::Node(p.master),
                xi: [0.0; 2],
                gap: gap.v,
                ..SlotState::unpaired(self.number, p.slave, ctx.position(p.slave)?.0)
            };
            points.push(apply_law(
                ctx, self.law, lambda_eqs, &local, &kin, areas[k], &mut state,
            ));
            states.push(state);
        }
        // Pairs are fixed: no search.
        Ok(0.0)
    }
}
