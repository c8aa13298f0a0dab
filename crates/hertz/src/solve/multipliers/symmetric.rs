//! The symmetric elimination: a symmetric tangent's multipliers eliminated into a symmetric
//! reduced system (see the parent module).

use super::rows::{RowBuilder, Rows};
use super::{eliminable, Eliminated, Group, MultiplierElimination, Solved};
use crate::error::Result;

/// How an eliminated group's slave unknowns follow from the reduced unknowns (the symmetric
/// elimination): x_S(a) = x₀(a) + Σ_{i≥p} Q[a, i] y_i + Σ_m F[a, m] x(masters[m]).
struct Substitution {
    /// The kept unknowns the group's multipliers act on besides its slave rows.
    masters: Vec<usize>,
    /// F = −Eᵀ B_M (r × masters, row-major): the slave unknowns' share of the masters' motion
    /// that keeps the constraints.
    f: Vec<f64>,
    /// x₀ = Eᵀ b_L: the slave unknowns' part that meets the constraints' right-hand side.
    x0: Vec<f64>,
}

impl Substitution {
    /// The substitution of eliminated group `el`, whose multipliers' rows are those of `rows`;
    /// `other` marks the unknowns that are not kept (multipliers, eliminated slave rows): a
    /// multiplier's entry there is round-off (see [`eliminable`]) and is dropped.
    fn new(el: &Eliminated, rows: &Rows, rhs: &[f64], other: &dyn Fn(usize) -> bool) -> Self {
        let (r, p) = (el.slave.len(), el.lambdas.len());
        let mut masters: Vec<usize> = Vec::new();
        // B_M by masters: one entry per multiplier.
        let mut b: Vec<Vec<f64>> = Vec::new();
        for (li, &l) in el.lambdas.iter().enumerate() {
            for (c, v) in rows.row(l) {
                if other(c) || v == 0.0 {
                    continue;
                }
                let m = match masters.iter().position(|&x| x == c) {
                    Some(m) => m,
                    None => {
                        masters.push(c);
                        b.push(vec![0.0; p]);
                        masters.len() - 1
                    }
                };
                b[m][li] += v;
            }
        }
        let nm = masters.len();
        let mut f = vec![0.0; r * nm];
        let mut x0 = vec![0.0; r];
        for a in 0..r {
            for (li, &l) in el.lambdas.iter().enumerate() {
                let e = el.e[li * r + a];
                x0[a] += e * rhs[l];
                for (m, bm) in b.iter().enumerate() {
                    f[a * nm + m] -= e * bm[li];
                }
            }
        }
        Substitution { masters, f, x0 }
    }
}

impl MultiplierElimination {
    /// [`MultiplierElimination::solve`] for a symmetric matrix: each eliminated group's slave
    /// unknowns are written as the displacements that keep its constraints, x_S = Q₁R⁻ᵀ(b_L −
    /// B_Mᵀ x_M) + Q₂ y (C = Q₁R its multipliers' columns on the slave rows, B_M on the others),
    /// so that the constraints hold for any y and x_M, and the equations are taken along the
    /// same substitution: x = T z + x₀, Tᵀ K T z = Tᵀ (b − K x₀) (Tᵀ B = 0 removes the
    /// eliminated multipliers). The reduced system is symmetric, positive definite where the
    /// bodies are held, and goes to a sparse Cholesky with a fill-reducing ordering; the
    /// multipliers follow from the slave rows, λ = E (b_S − K_S x). Only hard constraints are
    /// eliminated (a compliance's diagonal keeps its multiplier an unknown); multipliers kept
    /// make the reduced system indefinite, for a sparse LU, so without `general` the solve is
    /// then declined (false returned, `rhs` untouched).
    pub(super) fn solve_symmetric(
        &mut self,
        rows: &Rows,
        rhs: &mut [f64],
        groups: &[Group],
        general: bool,
        describe: &dyn Fn(usize) -> String,
    ) -> Result<bool> {
        let n = rows.ptr.len() - 1;
        let (eliminated, decoupled) = eliminable(rows, n, groups, true);
        let removed = eliminated.iter().map(|e| e.lambdas.len()).sum::<usize>()
            + decoupled
                .iter()
                .map(|&g| groups[g].lambdas.len())
                .sum::<usize>();
        if !general && removed < groups.iter().map(|g| g.lambdas.len()).sum::<usize>() {
            return Ok(false);
        }
        // Multipliers that leave the system, and the eliminated groups' slave unknowns.
        let mut gone = vec![false; n];
        let mut slave_of = vec![(usize::MAX, 0); n];
        for (g, el) in eliminated.iter().enumerate() {
            for &l in &el.lambdas {
                gone[l] = true;
            }
            for (a, &s) in el.slave.iter().enumerate() {
                slave_of[s] = (g, a);
            }
        }
        for &g in &decoupled {
            for &l in &groups[g].lambdas {
                gone[l] = true;
            }
        }
        let other = |c: usize| gone[c] || slave_of[c].0 != usize::MAX;
        let subs: Vec<Substitution> = eliminated
            .iter()
            .map(|el| Substitution::new(el, rows, rhs, &other))
            .collect();
        // The reduced unknowns: the kept ones, and each group's y_i (i ≥ p) in the place of its
        // slave unknown i.
        let mut pos = vec![usize::MAX; n];
        let mut kept = Vec::with_capacity(n);
        for i in 0..n {
            let taken = match slave_of[i] {
                (usize::MAX, _) => !gone[i],
                (g, a) => a >= eliminated[g].lambdas.len(),
            };
            if taken {
                pos[i] = kept.len();
                kept.push(i);
            }
        }
        let nk = kept.len();
        // The groups whose substitution holds a kept unknown: (group, its index among masters).
        let mut in_subs: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        for (g, sub) in subs.iter().enumerate() {
            for (m, &c) in sub.masters.iter().enumerate() {
                in_subs[c].push((g, m));
            }
        }
        // Column c of the full matrix in the reduced unknowns (row t's upper part only), and its
        // value at x₀.
        let column = |out: &mut RowBuilder, t: usize, c: usize, v: f64| -> f64 {
            if gone[c] {
                return 0.0;
            }
            let (g, a) = slave_of[c];
            if g == usize::MAX {
                if pos[c] >= t {
                    out.add(pos[c], v);
                }
                return 0.0;
            }
            let (el, sub) = (&eliminated[g], &subs[g]);
            let (r, p, nm) = (el.slave.len(), el.lambdas.len(), sub.masters.len());
            for i in p..r {
                let k = pos[el.slave[i]];
                if k >= t {
                    out.add(k, v * el.q[a * r + i]);
                }
            }
            for (m, &cm) in sub.masters.iter().enumerate() {
                if pos[cm] >= t {
                    out.add(pos[cm], v * sub.f[a * nm + m]);
                }
            }
            v * sub.x0[a]
        };
        let mut reduced_rows = RowBuilder::new(nk);
        let mut b = vec![0.0; nk];
        // Reduced row t: Σ over T's column t of w × (row i of the matrix) T.
        let mut t_col: Vec<(usize, f64)> = Vec::new();
        for (t, &i) in kept.iter().enumerate() {
            t_col.clear();
            match slave_of[i] {
                (usize::MAX, _) => {
                    t_col.push((i, 1.0));
                    for &(g, m) in &in_subs[i] {
                        let (el, sub) = (&eliminated[g], &subs[g]);
                        let nm = sub.masters.len();
                        for (a, &s) in el.slave.iter().enumerate() {
                            t_col.push((s, sub.f[a * nm + m]));
                        }
                    }
                }
                (g, col) => {
                    let el = &eliminated[g];
                    let r = el.slave.len();
                    for (a, &s) in el.slave.iter().enumerate() {
                        t_col.push((s, el.q[a * r + col]));
                    }
                }
            }
            for &(row, w) in &t_col {
                let mut at_x0 = 0.0;
                for (c, v) in rows.row(row) {
                    at_x0 += column(&mut reduced_rows, t, c, w * v);
                }
                b[t] += w * rhs[row] - at_x0;
            }
            reduced_rows.close(t);
        }
        let (reduced, vals) = reduced_rows.into_upper_pattern();
        if self
            .pattern
            .as_ref()
            .is_none_or(|p| p.col_ptr != reduced.col_ptr || p.row_idx != reduced.row_idx)
        {
            self.solver.reset();
            self.pattern = Some(reduced);
        }
        let reduced = self.pattern.as_ref().expect("set above");
        let describe_kept = |k: usize| describe(kept[k]);
        self.solver
            .factorize(reduced, &vals, false, &describe_kept)?;
        self.solver.solve_in_place(&mut b)?;
        // x: the kept unknowns, then each group's slave unknowns by its substitution.
        let mut x = vec![0.0; n];
        for (k, &i) in kept.iter().enumerate() {
            if slave_of[i].0 == usize::MAX {
                x[i] = b[k];
            }
        }
        for (el, sub) in eliminated.iter().zip(&subs) {
            let (r, p, nm) = (el.slave.len(), el.lambdas.len(), sub.masters.len());
            for a in 0..r {
                let mut v = sub.x0[a];
                for i in p..r {
                    v += el.q[a * r + i] * b[pos[el.slave[i]]];
                }
                for (m, &cm) in sub.masters.iter().enumerate() {
                    v += sub.f[a * nm + m] * x[cm];
                }
                x[el.slave[a]] = v;
            }
        }
        let solved = Solved {
            rows,
            gone: &gone,
            rhs,
        };
        solved.eliminated_multipliers(&eliminated, &mut x);
        solved.decoupled_multipliers(&decoupled, groups, &mut x, describe)?;
        rhs.copy_from_slice(&x);
        self.count(&eliminated, &decoupled, groups);
        Ok(true)
    }
}
