//! The symmetric elimination: a symmetric tangent's multipliers eliminated into a symmetric
//! reduced system (see the parent module), factorized once and applied to any right-hand side.

use super::rows::{RowBuilder, Rows};
use super::{eliminable, Eliminated, Group, Solved};
use crate::assembly::Pattern;
use crate::error::Result;
use crate::solve::linear::LinearSolver;

/// How an eliminated group's slave unknowns follow from the reduced unknowns:
/// x_S(a) = x₀(a) + Σ_{i≥p} Q[a, i] y_i + Σ_m F[a, m] x(masters[m]), x₀ = Eᵀ b_L.
struct Substitution {
    /// The kept unknowns the group's multipliers act on besides its slave rows.
    masters: Vec<usize>,
    /// F = −Eᵀ B_M (r × masters, row-major): the slave unknowns' share of the masters' motion
    /// that keeps the constraints.
    f: Vec<f64>,
}

impl Substitution {
    /// The substitution of eliminated group `el`, whose multipliers' rows are those of `rows`;
    /// `other` marks the unknowns that are not kept (multipliers, eliminated slave rows): a
    /// multiplier's entry there is round-off (see [`eliminable`]) and is dropped.
    fn new(el: &Eliminated, rows: &Rows, other: &dyn Fn(usize) -> bool) -> Self {
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
        for a in 0..r {
            for li in 0..p {
                let e = el.e[li * r + a];
                for (m, bm) in b.iter().enumerate() {
                    f[a * nm + m] -= e * bm[li];
                }
            }
        }
        Substitution { masters, f }
    }
}

/// A symmetric matrix with its multipliers eliminated: each eliminated group's slave unknowns
/// are written as the displacements that keep its constraints, x_S = Q₁R⁻ᵀ(b_L − B_Mᵀ x_M) +
/// Q₂ y (C = Q₁R its multipliers' columns on the slave rows, B_M on the others), so that the
/// constraints hold for any y and x_M, and the equations are taken along the same
/// substitution: x = T z + x₀, Tᵀ K T z = Tᵀ (b − K x₀) (Tᵀ B = 0 removes the eliminated
/// multipliers). The reduced system is symmetric, positive definite where the bodies are held,
/// for a sparse Cholesky with a fill-reducing ordering; the multipliers follow from the slave
/// rows, λ = E (b_S − K_S x). Only hard constraints are eliminated (a compliance's diagonal
/// keeps its multiplier an unknown, and the reduced system indefinite).
pub(super) struct Reduction {
    rows: Rows,
    eliminated: Vec<Eliminated>,
    decoupled: Vec<usize>,
    subs: Vec<Substitution>,
    /// Multipliers that leave the system.
    gone: Vec<bool>,
    /// (group, index among its slave unknowns) of an eliminated group's slave unknown.
    slave_of: Vec<(usize, usize)>,
    /// The reduced unknowns: the kept ones, and each group's y_i (i ≥ p) in the place of its
    /// slave unknown i; `pos` their places.
    kept: Vec<usize>,
    pos: Vec<usize>,
    /// The groups whose substitution holds a kept unknown: (group, its index among masters).
    in_subs: Vec<Vec<(usize, usize)>>,
    /// Multipliers of `groups` kept as unknowns.
    pub(super) kept_multipliers: usize,
}

impl Reduction {
    /// The reduction of the symmetric matrix `rows` (both triangles); its reduced matrix is
    /// [`Reduction::reduced_matrix`].
    pub(super) fn new(rows: Rows, groups: &[Group]) -> Reduction {
        let n = rows.ptr.len() - 1;
        let (eliminated, decoupled) = eliminable(&rows, n, groups, true);
        let removed = eliminated.iter().map(|e| e.lambdas.len()).sum::<usize>()
            + decoupled
                .iter()
                .map(|&g| groups[g].lambdas.len())
                .sum::<usize>();
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
            .map(|el| Substitution::new(el, &rows, &other))
            .collect();
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
        let mut in_subs: Vec<Vec<(usize, usize)>> = vec![Vec::new(); n];
        for (g, sub) in subs.iter().enumerate() {
            for (m, &c) in sub.masters.iter().enumerate() {
                in_subs[c].push((g, m));
            }
        }
        Reduction {
            rows,
            eliminated,
            decoupled,
            subs,
            gone,
            slave_of,
            kept,
            pos,
            in_subs,
            kept_multipliers: groups.iter().map(|g| g.lambdas.len()).sum::<usize>() - removed,
        }
    }

    /// Multipliers eliminated (through slave rows or as open points' own).
    pub(super) fn counts(&self) -> (&[Eliminated], &[usize]) {
        (&self.eliminated, &self.decoupled)
    }

    /// The reduced unknown at place k, as an unknown of the full system (a y_i as its slave
    /// unknown i).
    pub(super) fn unknown(&self, k: usize) -> usize {
        self.kept[k]
    }

    /// A vector `v` of the full system's unknowns that keeps the eliminated constraints (a
    /// rigid-body motion) in the reduced unknowns z, v = T z: a kept unknown's entry as it is,
    /// a group's y_i its slave entries along Q's column i (Q₂ᵀ F = 0, so the masters' share
    /// drops out).
    pub(super) fn restrict(&self, v: &[f64]) -> Vec<f64> {
        self.kept
            .iter()
            .map(|&i| match self.slave_of[i] {
                (usize::MAX, _) => v[i],
                (g, col) => {
                    let el = &self.eliminated[g];
                    let r = el.slave.len();
                    el.slave
                        .iter()
                        .enumerate()
                        .map(|(a, &s)| el.q[a * r + col] * v[s])
                        .sum()
                }
            })
            .collect()
    }

    /// T's column t: (row of the full system, weight).
    fn t_column(&self, t: usize, out: &mut Vec<(usize, f64)>) {
        out.clear();
        let i = self.kept[t];
        match self.slave_of[i] {
            (usize::MAX, _) => {
                out.push((i, 1.0));
                for &(g, m) in &self.in_subs[i] {
                    let (el, sub) = (&self.eliminated[g], &self.subs[g]);
                    let nm = sub.masters.len();
                    for (a, &s) in el.slave.iter().enumerate() {
                        out.push((s, sub.f[a * nm + m]));
                    }
                }
            }
            (g, col) => {
                let el = &self.eliminated[g];
                let r = el.slave.len();
                for (a, &s) in el.slave.iter().enumerate() {
                    out.push((s, el.q[a * r + col]));
                }
            }
        }
    }

    /// Tᵀ K T, upper triangle.
    pub(super) fn reduced_matrix(&self) -> (Pattern, Vec<f64>) {
        let mut reduced_rows = RowBuilder::new(self.kept.len());
        // Column c of the full matrix times v in the reduced unknowns, right of t only.
        let column = |out: &mut RowBuilder, t: usize, c: usize, v: f64| {
            if self.gone[c] {
                return;
            }
            let (g, a) = self.slave_of[c];
            if g == usize::MAX {
                if self.pos[c] >= t {
                    out.add(self.pos[c], v);
                }
                return;
            }
            let (el, sub) = (&self.eliminated[g], &self.subs[g]);
            let (r, p, nm) = (el.slave.len(), el.lambdas.len(), sub.masters.len());
            for i in p..r {
                let k = self.pos[el.slave[i]];
                if k >= t {
                    out.add(k, v * el.q[a * r + i]);
                }
            }
            for (m, &cm) in sub.masters.iter().enumerate() {
                if self.pos[cm] >= t {
                    out.add(self.pos[cm], v * sub.f[a * nm + m]);
                }
            }
        };
        let mut t_col = Vec::new();
        for t in 0..self.kept.len() {
            self.t_column(t, &mut t_col);
            for &(row, w) in &t_col {
                for (c, v) in self.rows.row(row) {
                    column(&mut reduced_rows, t, c, w * v);
                }
            }
            reduced_rows.close(t);
        }
        reduced_rows.into_upper_pattern()
    }

    /// The solution of the full system for `rhs`, with `solver` holding the reduced matrix's
    /// factorization.
    pub(super) fn apply(
        &self,
        solver: &mut dyn LinearSolver,
        rhs: &[f64],
        groups: &[Group],
        describe: &dyn Fn(usize) -> String,
    ) -> Result<Vec<f64>> {
        let n = rhs.len();
        // x₀ = Eᵀ b_L on the slave unknowns, and b − K x₀.
        let mut x = vec![0.0; n];
        for el in &self.eliminated {
            let r = el.slave.len();
            for (a, &s) in el.slave.iter().enumerate() {
                x[s] = el
                    .lambdas
                    .iter()
                    .enumerate()
                    .map(|(li, &l)| el.e[li * r + a] * rhs[l])
                    .sum();
            }
        }
        let mut y = rhs.to_vec();
        for (i, yi) in y.iter_mut().enumerate() {
            *yi -= self
                .rows
                .row(i)
                .filter(|&(c, _)| self.slave_of[c].0 != usize::MAX)
                .map(|(c, v)| v * x[c])
                .sum::<f64>();
        }
        let mut t_col = Vec::new();
        let mut b: Vec<f64> = (0..self.kept.len())
            .map(|t| {
                self.t_column(t, &mut t_col);
                t_col.iter().map(|&(row, w)| w * y[row]).sum()
            })
            .collect();
        solver.solve_in_place(&mut b)?;
        // x: the kept unknowns, then each group's slave unknowns by its substitution.
        for (k, &i) in self.kept.iter().enumerate() {
            if self.slave_of[i].0 == usize::MAX {
                x[i] = b[k];
            }
        }
        for (el, sub) in self.eliminated.iter().zip(&self.subs) {
            let (r, p, nm) = (el.slave.len(), el.lambdas.len(), sub.masters.len());
            for a in 0..r {
                let mut v = x[el.slave[a]];
                for i in p..r {
                    v += el.q[a * r + i] * b[self.pos[el.slave[i]]];
                }
                for (m, &cm) in sub.masters.iter().enumerate() {
                    v += sub.f[a * nm + m] * x[cm];
                }
                x[el.slave[a]] = v;
            }
        }
        let solved = Solved {
            rows: &self.rows,
            gone: &self.gone,
            rhs,
        };
        solved.eliminated_multipliers(&self.eliminated, &mut x);
        solved.decoupled_multipliers(&self.decoupled, groups, &mut x, describe)?;
        Ok(x)
    }
}
