//! The symmetric counterpart of a general tangent with multipliers, whose symmetric elimination
//! preconditions GMRES on the tangent itself (see the parent module), and the friction
//! multipliers' basis in which it is a good one.
//!
//! Each multiplier l has a row (its x-part G_l over the displacements, its diagonal d_l, and
//! terms on other multipliers) and a column c_l (its force on the displacements). The
//! counterpart takes it as
//! - **hard** (d_l = 0 up to round-off, or a compliance far stiffer than the bodies along
//!   c_l): its row is its column, G_l ≈ s_l c_lᵀ with s_l = G_l·c_l /
//!   c_l·c_l the least-squares factor; eliminated through the slave rows;
//! - **condensed** (d_l ≠ 0: a penalty's compliance, a sliding node's friction, the normal
//!   component of a friction force): λ_l = (b_l − s_l c_lᵀ x)/d_l substituted into the
//!   equilibrium, K − (s_l/d_l) c_l c_lᵀ (a penalty's stiffness: s_l/d_l ≤ 0, else s_l is taken as
//!   0 and λ_l solved from its own row first, its force moved to the right-hand side);
//! - **out** (an empty column: an open point's, a friction component no free unknown moves
//!   along): as it is, solved from its own row.
//!
//! Terms between multipliers (a sliding node's friction on its normal force) are left to GMRES.
//!
//! A friction force's multipliers are Cartesian components; their rows hold n·λ_T = 0 and, in
//! stick, the node to its anchor along the tangent plane. Rotated into the basis (t₁, t₂, m) of
//! [`friction_rotation`], the component along m is condensed (its row m·λ_T/c_T = …, its column
//! the normal force's), and each tangential one hard where the node sticks, condensed where it
//! slides (along the slip it is held at μλ; across it, a tie of compliance (1 − ρ)/(ρ c_T)).

use super::rows::{RowBuilder, Rows};
use super::{solve_small, Group};

/// A multiplier's diagonal below this fraction of its row's largest entry on the displacements
/// is round-off (a sticking friction component after the rotation), and the multiplier hard.
const HARD_TOL: f64 = 1e-12;

/// A compliant multiplier whose condensed stiffness along its column exceeds the bodies' by this
/// factor is taken as hard: a stiff penalty (1e7 on a block of E = 1000), a node barely sliding
/// (ρ → 1). Condensed, it would make the counterpart ill-conditioned, past what an algebraic
/// multigrid preconditions (PETSc's CG stopped with an indefinite preconditioner on the
/// Cattaneo–Mindlin example); tied, it differs from the tangent by 1/`STIFF_RATIO` of its
/// stiffness at most, which GMRES removes in a few iterations.
const STIFF_RATIO: f64 = 1e2;

/// How the counterpart takes a multiplier (see the module doc); a condensed one's `k` is its
/// place in [`Counterpart::condensed`].
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    Hard { scale: f64 },
    Condensed { s: f64, d: f64, k: usize },
    Out,
}

/// How a general tangent's symmetric counterpart is reduced ([`super::symmetric::Reduction`]),
/// and how a right-hand side of the tangent becomes one of the counterpart.
pub(super) struct Counterpart {
    /// The groups of the reduction: each group's hard multipliers with its slave rows, every
    /// condensed and out multiplier alone.
    pub(super) groups: Vec<Group>,
    /// Per unknown, what its row's right-hand side is divided by (a hard multiplier's s_l).
    scale: Vec<f64>,
    condensed: Vec<Condensed>,
}

/// A condensed multiplier: l, d_l and c_l over the displacement rows.
struct Condensed {
    l: usize,
    d: f64,
    column: Vec<(usize, f64)>,
}

/// Multiplier l's row and column over the displacements, read once: its diagonal d_l and, for
/// every displacement c in its row's pattern, (c, G_l[c], c_l[c]).
struct Lines {
    d: f64,
    entries: Vec<(usize, f64, f64)>,
}

impl Lines {
    fn new(rows: &Rows, l: usize, multiplier: &[bool]) -> Lines {
        let mut d = 0.0;
        let mut entries = Vec::new();
        for (c, v) in rows.row(l) {
            if c == l {
                d = v;
            } else if !multiplier[c] {
                entries.push((c, v, rows.at(c, l)));
            }
        }
        Lines { d, entries }
    }

    /// c_l over the displacements.
    fn column(&self) -> Vec<(usize, f64)> {
        self.entries.iter().map(|&(c, _, t)| (c, t)).collect()
    }
}

impl Counterpart {
    /// The counterpart of `rows` (structurally symmetric) with the multipliers of `groups`: the
    /// displacements' block symmetrized and stiffened by the condensed multipliers, the hard
    /// multipliers' rows their columns, the condensed ones' columns empty. None where a
    /// multiplier's row is neither its column nor compliant (G_l ⟂ c_l, d_l = 0), or where one
    /// would be condensed without `condense`.
    pub(super) fn new(
        rows: &Rows,
        groups: &[Group],
        condense: bool,
    ) -> Option<(Rows, Counterpart)> {
        let n = rows.ptr.len() - 1;
        let mut multiplier = vec![false; n];
        for g in groups {
            for &l in &g.lambdas {
                multiplier[l] = true;
            }
        }
        let mut role: Vec<Option<Role>> = vec![None; n];
        let mut scale = vec![1.0; n];
        let mut condensed = Vec::new();
        for &l in groups.iter().flat_map(|g| &g.lambdas) {
            let lines = Lines::new(rows, l, &multiplier);
            let r = classify(rows, &lines, condensed.len())?;
            match r {
                Role::Hard { scale: s } => scale[l] = s,
                Role::Condensed { d, .. } if condense => condensed.push(Condensed {
                    l,
                    d,
                    column: lines.column(),
                }),
                Role::Condensed { .. } => return None,
                Role::Out => {}
            }
            role[l] = Some(r);
        }
        let mut out = RowBuilder::new(n);
        for i in 0..n {
            match role[i] {
                Some(Role::Out) => rows.row(i).for_each(|(c, v)| out.add(c, v)),
                Some(Role::Hard { .. }) => {
                    for (c, _) in rows.row(i) {
                        out.add(c, if multiplier[c] { 0.0 } else { rows.at(c, i) });
                    }
                }
                Some(Role::Condensed { s, d, .. }) => {
                    for (c, _) in rows.row(i) {
                        let v = if c == i {
                            d
                        } else if multiplier[c] {
                            0.0
                        } else {
                            s * rows.at(c, i)
                        };
                        out.add(c, v);
                    }
                }
                None => {
                    for (c, v) in rows.row(i) {
                        let w = match role[c] {
                            Some(Role::Condensed { .. }) => 0.0,
                            Some(_) => v,
                            None if c == i => v,
                            None => 0.5 * (v + rows.at(c, i)),
                        };
                        out.add(c, w);
                        if let Some(Role::Condensed { s, d, k }) = role[c] {
                            // −(s/d) c_l c_lᵀ on row i (c_l's entry v at i).
                            let f = -(s / d) * v;
                            if f != 0.0 {
                                for &(j, t) in &condensed[k].column {
                                    out.add(j, f * t);
                                }
                            }
                        }
                    }
                }
            }
            out.close(i);
        }
        let mut reduction_groups = Vec::new();
        for g in groups {
            let hard: Vec<usize> = g
                .lambdas
                .iter()
                .copied()
                .filter(|&l| matches!(role[l], Some(Role::Hard { .. })))
                .collect();
            for &l in &g.lambdas {
                if !matches!(role[l], Some(Role::Hard { .. })) {
                    reduction_groups.push(Group {
                        slave: Vec::new(),
                        lambdas: vec![l],
                    });
                }
            }
            if !hard.is_empty() {
                reduction_groups.push(Group {
                    slave: g.slave.clone(),
                    lambdas: hard,
                });
            }
        }
        Some((
            out.into_rows(),
            Counterpart {
                groups: reduction_groups,
                scale,
                condensed,
            },
        ))
    }

    /// The counterpart's right-hand side for the tangent's `b`: hard multipliers' rows divided
    /// by their s_l, the condensed ones' forces d_l⁻¹ b_l c_l moved to the right.
    pub(super) fn rhs(&self, b: &[f64]) -> Vec<f64> {
        let mut w: Vec<f64> = b.iter().zip(&self.scale).map(|(v, s)| v / s).collect();
        for c in &self.condensed {
            let f = b[c.l] / c.d;
            for &(i, t) in &c.column {
                w[i] -= t * f;
            }
        }
        w
    }
}

/// A multiplier's role from its `lines`: its row's x-part against its column; `k` the place a
/// condensed one takes.
fn classify(rows: &Rows, lines: &Lines, k: usize) -> Option<Role> {
    let (mut rc, mut cc, mut size) = (0.0, 0.0, 0.0f64);
    for &(_, v, t) in &lines.entries {
        rc += v * t;
        cc += t * t;
        size = size.max(v.abs());
    }
    if cc == 0.0 {
        return Some(Role::Out);
    }
    let (s, d) = (rc / cc, lines.d);
    let hard = d.abs() <= HARD_TOL * size
        || (s / d < 0.0 && -s / d * cc * cc > STIFF_RATIO * stiffness_along(rows, lines));
    if hard {
        return (rc != 0.0).then_some(Role::Hard { scale: s });
    }
    // A stiffness −s/d < 0 would make the counterpart indefinite: the row is solved first.
    let s = if s / d <= 0.0 { s } else { 0.0 };
    Some(Role::Condensed { s, d, k })
}

/// cᵀ K c for a multiplier's column c over the displacements: the bodies' stiffness along it.
fn stiffness_along(rows: &Rows, lines: &Lines) -> f64 {
    let e = &lines.entries;
    e.iter()
        .map(|&(i, _, ci)| ci * e.iter().map(|&(j, _, cj)| rows.at(i, j) * cj).sum::<f64>())
        .sum()
}

/// A change of basis of every friction force's multipliers (a group of dim + 1 multipliers
/// whose slave node has all dim rows free: the Cartesian components λ_T, then λ_N) as entries
/// (k, l, P_kl) of `super::Transform`: λ_T = t₁α₁ (+ t₂α₂) + mβ, with m the direction whose
/// friction force acts on the slave rows as the normal force does (C_T m ∥ c_N: the normal)
/// and, in 3D, t₁, t₂ the principal directions of the tangential block of the friction rows
/// (along and across the slip where the node slides).
pub(super) fn friction_rotation(rows: &Rows, groups: &[Group]) -> Vec<(usize, usize, f64)> {
    let mut out = Vec::new();
    for g in groups {
        let dim = g.lambdas.len().saturating_sub(1);
        if !(2..=3).contains(&dim) || g.slave.len() != dim {
            continue;
        }
        let (lt, ln) = (&g.lambdas[..dim], g.lambdas[dim]);
        let mut a: Vec<f64> = g
            .slave
            .iter()
            .flat_map(|&s| lt.iter().map(move |&l| rows.at(s, l)))
            .collect();
        let mut f: Vec<f64> = g.slave.iter().map(|&s| rows.at(s, ln)).collect();
        let Some(m) = solve_small(&mut a, &mut f, dim) else {
            continue;
        };
        let norm = m.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm > 0.0) || !norm.is_finite() {
            continue;
        }
        let m: Vec<f64> = m.iter().map(|v| v / norm).collect();
        let basis = if dim == 2 {
            vec![vec![-m[1], m[0]], m]
        } else {
            let (u1, u2) = tangent_pair(&m);
            // The symmetric part of the friction rows' own block, in the tangent plane.
            let at = |i: usize, j: usize| 0.5 * (rows.at(lt[i], lt[j]) + rows.at(lt[j], lt[i]));
            let q = |x: &[f64], y: &[f64]| -> f64 {
                (0..3)
                    .flat_map(|i| (0..3).map(move |j| (i, j)))
                    .map(|(i, j)| x[i] * at(i, j) * y[j])
                    .sum()
            };
            let (b11, b12, b22) = (q(&u1, &u1), q(&u1, &u2), q(&u2, &u2));
            let theta = 0.5 * (2.0 * b12).atan2(b11 - b22);
            let (c, s) = (theta.cos(), theta.sin());
            let t1: Vec<f64> = (0..3).map(|i| c * u1[i] + s * u2[i]).collect();
            let t2: Vec<f64> = (0..3).map(|i| -s * u1[i] + c * u2[i]).collect();
            vec![t1, t2, m]
        };
        for (k, b) in basis.iter().enumerate() {
            for (j, &w) in b.iter().enumerate() {
                out.push((lt[k], lt[j], w));
            }
        }
    }
    out
}

/// Two unit vectors orthogonal to the unit `m` and to each other.
fn tangent_pair(m: &[f64]) -> (Vec<f64>, Vec<f64>) {
    // The axis least along m, made orthogonal to it.
    let axis = (0..3)
        .min_by(|&i, &j| m[i].abs().total_cmp(&m[j].abs()))
        .expect("three axes");
    let mut u: Vec<f64> = (0..3).map(|i| -m[axis] * m[i]).collect();
    u[axis] += 1.0;
    let norm = u.iter().map(|v| v * v).sum::<f64>().sqrt();
    u.iter_mut().for_each(|v| *v /= norm);
    let w = vec![
        m[1] * u[2] - m[2] * u[1],
        m[2] * u[0] - m[0] * u[2],
        m[0] * u[1] - m[1] * u[0],
    ];
    (u, w)
}
