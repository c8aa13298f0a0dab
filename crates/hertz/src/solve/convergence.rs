//! The convergence test of a Newton iterate: OOFEM's relative force residual per DOF-id group
//! (spec §1.3), the multipliers' gap rows against rtolf times the largest displacement, and the
//! round-off floor of the forces (the penalty forces', and every element's and multiplier's
//! force summed into a residual entry), below which a residual that no longer falls is
//! accepted.

use crate::assembly::DofMap;
use crate::contact::{BranchRule, SlotLinearization};
use crate::model::{Analysis, Model};

/// A residual that no longer falls and is within this many times the round-off estimate of the
/// penalty forces counts as converged.
const ROUNDOFF_FACTOR: f64 = 16.0;

/// What the test looks at: the free equations' residual and external forces, the element-by-element
/// force norms per DOF id, the last step and the current state.
pub struct Residual<'r> {
    pub rhs: &'r [f64],
    pub f_ext: &'r [f64],
    pub ebe: &'r [f64; 4],
    pub du: &'r [f64],
    pub u: &'r [f64],
}

/// The convergence test's verdict on one iteration.
pub struct Check {
    /// Largest relative (or absolute) force error over the DOF groups.
    pub worst: f64,
    pub converged: bool,
    /// Not converged, but every group is within its round-off floor.
    pub on_floor: bool,
    /// The penalty forces' round-off is most of that floor (else the elements' and multipliers').
    pub penalty_floor: bool,
    /// On the floor: the residual over the tolerance.
    pub floor_ratio: Option<f64>,
    /// The largest round-off floor estimate over the tolerance.
    pub floor_excess: f64,
}

impl Check {
    /// On the round-off floor, a residual is accepted once Newton stops gaining on it: when it
    /// is more than half the `last` iteration's (iteration `it`).
    pub fn accept_on_floor(&mut self, it: usize, last: Option<f64>) {
        if !self.converged && self.on_floor && it > 0 && last.is_some_and(|l| self.worst > 0.5 * l)
        {
            self.converged = true;
        }
    }
}

/// OOFEM's convergence test per DOF-id group (spec §1.3), with the round-off floor of penalty
/// forces; multiplier rows (gaps) against rtolf times the largest displacement.
pub fn check(
    model: &Model,
    dofs: &DofMap,
    r: &Residual,
    a: &Analysis,
    it: usize,
    points: &[SlotLinearization],
) -> Check {
    let (rhs, f_ext, ebe, du, u) = (r.rhs, r.f_ext, r.ebe, r.du, r.u);
    let nf_u = dofs.n_free - dofs.n_lambda;
    let mut num = [0.0; 4];
    let mut den = [0.0; 4];
    let mut dd = [0.0; 4];
    let mut uu = [0.0; 4];
    let mut floor = [0.0; 4];
    let mut present = [false; 4];
    let mut umax = 0.0f64;
    for i in 0..nf_u {
        let g = dofs.primary_dof_id[i] as usize;
        present[g] = true;
        num[g] += rhs[i] * rhs[i];
        den[g] += f_ext[i] * f_ext[i];
        dd[g] += du[i] * du[i];
        uu[g] += u[i] * u[i];
        umax = umax.max(u[i].abs());
    }
    // Round-off of closed penalty points: ε·|force row|·X/|g| per entry, X the size of the
    // coordinates the gap is a difference of.
    let scale = crate::model::queries::coordinate_size(model);
    for p in points
        .iter()
        .filter(|p| p.closed && p.rule == BranchRule::Penalty)
    {
        if p.gap == 0.0 || p.closed_fe.is_empty() {
            continue;
        }
        for (k, &code) in p.codes.iter().enumerate() {
            let stiff = p.closed_fe[k].abs() / p.gap.abs();
            for (e, w) in dofs.entries(code) {
                if e < nf_u {
                    let g = dofs.primary_dof_id[e] as usize;
                    floor[g] += (w * stiff * f64::EPSILON * scale).powi(2);
                }
            }
        }
    }
    // The round-off of the sums themselves, in every entry: ε times the forces summed into the
    // residual, the elements' (`ebe`, all their components: an element's x force is computed
    // from all its stresses) and the closed multiplier points'. A block pressed along z has
    // x and y residuals of ε times its z forces, not of its x and y forces (which vanish).
    let multiplier_forces: f64 = points
        .iter()
        .filter(|p| p.closed && matches!(p.rule, BranchRule::Multiplier { .. }))
        .flat_map(|p| p.closed_fe.iter().map(|f| f * f))
        .sum();
    // Where contact holds, the gaps are differences of positions X + u that carry ε·X of
    // round-off (X the coordinates' size): the displacements it holds are that uncertain, and
    // the forces in proportion, ε·X/max|u| of themselves. Negligible near the origin (X = 10,
    // |u| = 0.1: 2e-14); 10³ from it a large-deformation patch never met rtolf 1e-12.
    let closed = points.iter().any(|p| p.closed);
    let positions = if closed && umax > 0.0 {
        (f64::EPSILON * scale / umax).powi(2)
    } else {
        0.0
    };
    let base = (ebe.iter().sum::<f64>() + multiplier_forces) * (f64::EPSILON.powi(2) + positions);
    let mut worst: f64 = 0.0;
    let mut ok = true;
    let mut within_floor = true;
    let mut floor_ratio: Option<f64> = None;
    let mut floor_excess = 0.0f64;
    // Multiplier rows: the gaps, against rtolf times the largest displacement (and their own
    // round-off).
    let gap_tol = (a.rtolf * umax).max(ROUNDOFF_FACTOR * f64::EPSILON * scale);
    for i in nf_u..dofs.n_free {
        let e = rhs[i].abs() / gap_tol * a.rtolf;
        worst = worst.max(e);
        if !(rhs[i].abs() <= gap_tol) {
            ok = false;
            within_floor = false;
        }
    }
    for g in 1..4 {
        if !present[g] {
            continue;
        }
        let d = den[g] + ebe[g];
        let reference = if d < 1e-6 { 1.0 } else { d.sqrt() };
        let fe = num[g].sqrt() / reference;
        worst = worst.max(fe);
        let floor_rel = ROUNDOFF_FACTOR * (floor[g] + base).sqrt() / reference;
        // The penalty's estimate itself, without the safety factor of the acceptance test.
        floor_excess = floor_excess.max(floor[g].sqrt() / reference / a.rtolf);
        if !(fe <= a.rtolf) {
            ok = false;
            if fe <= floor_rel {
                floor_ratio = Some(floor_ratio.unwrap_or(0.0).max(fe / a.rtolf));
            } else {
                within_floor = false;
            }
        }
        if a.rtold > 0.0 && it > 0 {
            let de = if uu[g] < 1e-6 {
                dd[g].sqrt()
            } else {
                (dd[g] / uu[g]).sqrt()
            };
            if !(de <= a.rtold) {
                ok = false;
            }
        }
    }
    Check {
        worst,
        converged: ok,
        on_floor: !ok && within_floor && floor_ratio.is_some(),
        penalty_floor: floor.iter().sum::<f64>() > base,
        floor_ratio,
        floor_excess,
    }
}

/// The warning for a tolerance below the round-off of the forces themselves (no penalty's).
pub fn precision_warning(ratio: f64, rtolf: f64) -> String {
    format!(
        "the residual stalled at {:.1e}, {ratio:.0e} times the tolerance rtolf {rtolf:.0e}, on the \
         round-off floor of the element and contact forces summed into it: rtolf is below what \
         double precision resolves here and the step was accepted there",
        ratio * rtolf
    )
}

/// The warning for penalty forces whose round-off exceeds the tolerance, with the penalty each
/// penalty condition has in effect (`penalties`: its number, its smallest and largest over its
/// slots) and the most it could have to stay within it.
pub fn penalty_warning(penalties: &[(usize, f64, f64)], ratio: f64, rtolf: f64) -> String {
    let suggestions: Vec<String> = penalties
        .iter()
        .map(|&(number, lo, hi)| {
            let effect = if lo == hi {
                format!("penalty {hi:.0e}")
            } else {
                format!("penalties {lo:.0e} to {hi:.0e}")
            };
            format!(
                "condition {number}: {effect}, suggested at most {:.0e}",
                hi / ratio
            )
        })
        .collect();
    format!(
        "the residual stalled at {:.1e}, {ratio:.0e} times the tolerance rtolf {rtolf:.0e}, on the \
         round-off floor of the penalty forces: the penalty is larger than double precision \
         resolves and the step was accepted there ({})",
        ratio * rtolf,
        suggestions.join("; ")
    )
}
