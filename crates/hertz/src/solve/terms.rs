//! Terms a driver adds to the bodies' equations in every Newton iteration of a step: a time
//! integrator's inertia (the forces M·a(u) and their tangent a₀·M) or damping. The Newton
//! iteration takes them with the step's target and knows nothing else of them; statics adds
//! the follower loads' forces ([`FollowerTerms`]), nothing without them ([`Statics`]).

use crate::assembly::{Contribution, DofMap, Pattern};
use crate::model::Model;
use crate::solid::follower::FollowerLoads;

/// Forces that depend on the state, with their tangent, added to the internal forces.
pub trait StepTerms {
    /// Add the terms' forces at the primary state `u` to `f_int` (free, then prescribed
    /// equations).
    fn add_forces(&self, u: &[f64], f_int: &mut [f64]);

    /// Add their tangent at `u` over the free equations to the values `k` on `pattern` (one
    /// triangle if it is symmetric).
    fn add_tangent(&self, u: &[f64], pattern: &Pattern, k: &mut [f64]);

    /// A factor s: the terms add s times the elements' own forces and tangent (not the
    /// contact's): stiffness-proportional damping. 0 without.
    fn element_scale(&self) -> f64 {
        0.0
    }

    /// Whether the tangent is the same at every state and in every step (then a linear
    /// problem's factorization is kept from one iteration and step to the next).
    fn constant_tangent(&self) -> bool {
        true
    }

    /// Add the squares of the terms' forces at `u` to `ebe`, per DOF id, as the elements'
    /// are: the scale the convergence test measures the residual against and the round-off
    /// it expects (inertia can be most of a step's forces).
    fn add_force_norms(&self, _u: &[f64], _dofs: &DofMap, _ebe: &mut [f64; 4]) {}
}

/// No terms: statics.
#[derive(Debug, Clone, Copy, Default)]
pub struct Statics;

impl StepTerms for Statics {
    fn add_forces(&self, _u: &[f64], _f_int: &mut [f64]) {}
    fn add_tangent(&self, _u: &[f64], _pattern: &Pattern, _k: &mut [f64]) {}
}

/// Two drivers' terms together (a time integrator's inertia and the follower loads).
pub struct Both<'a>(pub &'a dyn StepTerms, pub &'a dyn StepTerms);

impl StepTerms for Both<'_> {
    fn add_forces(&self, u: &[f64], f_int: &mut [f64]) {
        self.0.add_forces(u, f_int);
        self.1.add_forces(u, f_int);
    }
    fn add_tangent(&self, u: &[f64], pattern: &Pattern, k: &mut [f64]) {
        self.0.add_tangent(u, pattern, k);
        self.1.add_tangent(u, pattern, k);
    }
    fn constant_tangent(&self) -> bool {
        self.0.constant_tangent() && self.1.constant_tangent()
    }
    fn element_scale(&self) -> f64 {
        self.0.element_scale() + self.1.element_scale()
    }
    fn add_force_norms(&self, u: &[f64], dofs: &DofMap, ebe: &mut [f64; 4]) {
        self.0.add_force_norms(u, dofs, ebe);
        self.1.add_force_norms(u, dofs, ebe);
    }
}

/// The follower loads at given load factors: forces that turn and stretch with the boundary.
pub struct FollowerTerms<'a> {
    pub loads: &'a FollowerLoads,
    pub model: &'a Model,
    pub dofs: &'a DofMap,
    /// The load factor of every load of the model (its time function's value in the step).
    pub scale: Vec<f64>,
}

impl FollowerTerms<'_> {
    fn contributions(&self, u: &[f64], want_k: bool) -> Vec<Contribution> {
        self.loads
            .contributions(self.model, self.dofs, u, &self.scale, want_k)
    }
}

impl StepTerms for FollowerTerms<'_> {
    fn add_forces(&self, u: &[f64], f_int: &mut [f64]) {
        for c in self.contributions(u, false) {
            for (&code, &fa) in c.codes.iter().zip(&c.fe) {
                for (p, wp) in self.dofs.entries(code) {
                    f_int[p] += wp * fa;
                }
            }
        }
    }

    fn add_tangent(&self, u: &[f64], pattern: &Pattern, k: &mut [f64]) {
        let nf = self.dofs.n_free;
        for c in self.contributions(u, true) {
            let nd = c.codes.len();
            for (a, &ca) in c.codes.iter().enumerate() {
                for (p, wp) in self.dofs.entries(ca).filter(|&(p, _)| p < nf) {
                    for (b, &cb) in c.codes.iter().enumerate() {
                        for (q, wq) in self.dofs.entries(cb).filter(|&(q, _)| q < nf) {
                            // Both triangles: the model's pattern is not symmetric.
                            k[pattern.position(p, q)] += wp * wq * c.ke[a * nd + b];
                        }
                    }
                }
            }
        }
    }

    fn constant_tangent(&self) -> bool {
        self.loads.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assembly::DofMap;
    use crate::contact::ContactSystem;
    use crate::solve::newton::NewtonContext;
    use crate::solve::report::{Silent, StepInfo};
    use crate::solve::SolveParams;

    /// A nonlinear spring to ground on free equation 0: f = k·u + c·u³.
    struct Spring {
        k: f64,
        c: f64,
    }

    impl StepTerms for Spring {
        fn add_forces(&self, u: &[f64], f_int: &mut [f64]) {
            f_int[0] += self.k * u[0] + self.c * u[0].powi(3);
        }
        fn add_tangent(&self, u: &[f64], pattern: &Pattern, k: &mut [f64]) {
            k[pattern.position(0, 0)] += self.k + 3.0 * self.c * u[0] * u[0];
        }
        fn constant_tangent(&self) -> bool {
            self.c == 0.0
        }
    }

    /// The Newton iteration takes a driver's terms in its residual and tangent: a bar (k = 100)
    /// with a spring to ground (k = 300) at its free end, loaded by 1, moves by 1/400 exactly in
    /// one iteration; with a cubic spring (c = 10⁶) it converges to the root of
    /// 400u + 10⁶u³ = 1 quadratically.
    #[test]
    fn newton_solves_with_a_drivers_terms() {
        let text =
            "bar.out\nbar\nNonLinearStatic nsteps 1 controlmode 1 rtolf 1e-12 manrmsteps 1\n\
                    domain 1dTruss\nOutputManager\n\
                    ndofman 2 nelem 1 ncrosssect 1 nmat 1 nbc 2 nic 0 nltf 1 nset 2\n\
                    node 1 coords 1 0\nnode 2 coords 1 1\n\
                    Truss1d 1 nodes 2 1 2 crossSect 1 mat 1\n\
                    SimpleCS 1 area 1 material 1 set 1\nIsoLE 1 d 0 E 100 n 0 tAlpha 0\n\
                    BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n\
                    NodalLoad 2 loadTimeFunction 1 dofs 1 1 Components 1 1 set 1\n\
                    ConstantFunction 1 f(t) 1\nSet 1 nodes 1 2\nSet 2 nodes 1 1\n";
        let model = crate::input::read_model_str(text, "bar.in").unwrap().model;
        let contact = ContactSystem::new(&model).unwrap();
        let dofs = DofMap::new(&model, &contact.extra_dofs()).unwrap();
        assert_eq!(dofs.n_free, 1);
        let params = SolveParams::default();
        let (mut ctx, _) = NewtonContext::new(&model, &dofs, contact, &params, &Silent).unwrap();
        let a = &model.analysis;
        for (c, exact) in [(0.0, 1.0 / 400.0), (1e6, cubic_root(400.0, 1e6, 1.0))] {
            let spring = Spring { k: 300.0, c };
            let mut u = vec![0.0; dofs.n_primary()];
            let f_ext = [1.0, 0.0];
            let mut info = StepInfo::default();
            let up = vec![0.0; dofs.n_prescribed];
            assert!(ctx
                .newton(&mut u, (&f_ext, &up), a, &mut info, &spring)
                .unwrap());
            assert!(
                (u[0] - exact).abs() < 1e-12 * exact,
                "c {c}: {} vs {exact}",
                u[0]
            );
            let h = &info.residual_history;
            if c == 0.0 {
                assert_eq!(info.iterations, 1, "{h:?}");
            } else {
                let n = h.len();
                assert!(
                    n <= 8 && h[n - 1] <= 1e-3 * h[n - 2] * h[n - 2].max(1e-9).sqrt(),
                    "{h:?}"
                );
            }
        }
    }

    /// The root of k u + c u³ = f (Newton in f64, for the reference).
    fn cubic_root(k: f64, c: f64, f: f64) -> f64 {
        let mut u = f / k;
        for _ in 0..100 {
            u -= (k * u + c * u.powi(3) - f) / (k + 3.0 * c * u * u);
        }
        u
    }
}
