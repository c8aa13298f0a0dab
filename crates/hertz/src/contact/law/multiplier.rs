//! Lagrange multiplier law (λ > 0 in compression), with a complementarity active set on the
//! constraint h (g, or max(g, e) near an open end: see below): active while the point counts
//! and λ − c·h > −c·gap_tol (so a node that touches, g = 0, with no force yet, λ = 0, is active
//! — a body that starts touching under a load is held);
//! * active: r_u = −λ·B, r_λ = −h; K_uu = −λ·∂B (geometric), K_uλ = −B, K_λu = −∇h;
//! * inactive: r_λ = λ, K_λλ = 1 (so λ = 0).
//!
//! The geometric part is kept at any force, unlike the penalty law's (see
//! [`super::Laws::geometric_allowed`]): the gap row holds the node on the master, so a large λ
//! is no sign of an iterate deep inside it. It comes from the discretization — nodal pressures of a
//! stiff slave with facets finer than a soft master's exceed E — and dropping the geometric part
//! there makes Newton converge linearly (BENCHMARKS.md, "Evidence behind design choices").
//!
//! The weight w only switches the constraint: in the limit of an infinite penalty, the penalty law
//! holds g = 0 wherever w > 0, and a node it presses towards the end of w's ramp (e → 0, with e
//! the distance past the ramp's far end) is held there with a finite force ε·w·(−g) and g < 0.
//! Holding g = 0 while w > 0 and nothing once w = 0 has no solution for such a node (held, it is
//! pushed out past the ramp; let go, it comes back in below the master), and Newton alternates
//! between the two. So near an open end the constraint is h = max(g, e) = 0: g = 0 inside the
//! ramp, or e = 0 with g < 0 at its end, the force along B in both (as the penalty's).
//!
//! Coulomb friction without a penalty: the friction force λ_T (a vector in Cartesian components,
//! the internal force on the node; its equations hold n·λ_T = 0) is a multiplier too, spread like
//! the normal force ([`SlipKinematics::share`]), with the complementarity function of Alart and
//! Curnier solved by a semismooth Newton method:
//!   C_T = (λ_T − proj_{|·| ≤ μ⟨λ⟩}(P λ_T + c_T g_T)) / c_T = 0,   g_T = P (x_s − x_a),
//! P = I − n ⊗ n, x_a the anchor: the master's material point the node was at when the last step
//! converged. Stick (|P λ_T + c_T g_T| ≤ μλ) makes it g_T = 0 and n·λ_T = 0; slip makes λ_T =
//! μλ·v/|v| (v = P λ_T + c_T g_T), along the slip, with |λ_T| = μλ. The branch is taken from the
//! current iterate (a generalized Jacobian of the kink); c_T only sets the Newton path. Divided
//! by c_T, each row is a length, as the gap rows are. Inactive points hold λ_T = 0.
//!
//! A penalty with friction is solved in this form too, with the penalty's compliance (1/ε, and
//! 1/ε_T in [`SlipKinematics::compliance`]) in the rows:
//!   C_N = λ − max(0, λ − c (w·g + λ/ε)),   C_T = (λ_T − proj(P λ_T + c_T (g_T − P λ_T/ε_T))) / c_T,
//! whose solutions are exactly the penalty's (active: λ = −ε·w·g; stick: λ_T = ε_T g_T; slip:
//! λ_T = μλ along g_T with ε_T |g_T| > μλ), with g_T measured from the anchor the last step left
//! (the elastic slip stays in it). The Newton iteration differs: the forces are held between
//! iterates, so a gap error of an iterate (10⁻³ after a step along a curved die, against a
//! penetration λ/ε of 10⁻⁶ with the penalty from the mesh) is an error of a length in the rows,
//! not an error ε times it in the friction force, and stick or slip is decided from the held
//! force plus c_T times the slip instead of ε_T times it. c and c_T are capped at ε and ε_T: at
//! the cap the rules are the penalty's own.

use super::{linearization, Laws, SlipKinematics, SlotKinematics};
use crate::contact::dual::{Dual, Jet};
use crate::contact::slot::{BranchRule, SlotLinearization};

/// c of a complementarity rule capped at the penalty 1/`compliance` (none: c).
fn capped(c: f64, compliance: f64) -> f64 {
    if compliance > 0.0 {
        c.min(1.0 / compliance)
    } else {
        c
    }
}

/// `codes`: the displacement codes, then the equations of the multipliers `lambdas`: the
/// friction force's components (if any) and last the normal force. `compliance`: 1/ε of a
/// penalty condition solved in this form, else 0. `free`: whether a displacement code moves with
/// a free equation. Returns the point and, for an active point with friction, whether it
/// sticks and the friction force's magnitude.
///
/// A friction component along an axis on which every node of the point is held (a plate with
/// u_z = 0 everywhere, pressed on a fixed block) does no work on any free equation: its column
/// is empty, and so is its row where the rule's kink leaves no λ_T dependence (a node sliding at
/// the start of a step). It is held at zero (its row λ_T,k = 0): the only Coulomb force in a
/// slide, since no slip can happen along the axis, and a valid one in stick, where the support
/// takes any force along it.
pub fn evaluate(
    laws: &Laws,
    lambdas: &[f64],
    mut codes: Vec<usize>,
    eqs: std::ops::Range<usize>,
    k: &SlotKinematics,
    compliance: f64,
    free: &dyn Fn(usize) -> bool,
) -> (SlotLinearization, Option<(bool, f64)>) {
    let m = k.b.len();
    let nt = eqs.len() - 1;
    codes.extend(eqs);
    let mm = codes.len();
    let lambda = lambdas[nt];
    let mut lambda_t = [0.0; 3];
    lambda_t[..nt].copy_from_slice(&lambdas[..nt]);
    let c = capped(laws.c, compliance);
    // The constraint the normal row holds: g; near an open end max(g, e); with a penalty's
    // compliance w·g (the penalty's force is ε·w·⟨−g⟩; the weight only switches a multiplier).
    let h = match &k.past_end {
        _ if compliance > 0.0 => k.weight.product(&k.gap),
        Some(e) if e.v > k.gap.v => e.clone(),
        _ => k.gap.clone(),
    };
    let rule = BranchRule::Multiplier {
        lambda,
        lambda_t,
        tangential: nt,
        c,
        compliance,
        tol: laws.gap_tol,
    };
    let counts = k.weight.v > 0.0 || (compliance == 0.0 && k.past_end.is_some());
    // A multiplier whose force moves no free unknown (a slave node held along its normal by a
    // support, against a master that does not move) repeats the support's constraint: it is
    // undetermined, and the tangent singular ("held by contact alone"). It holds nothing; the
    // support takes the force. (With a penalty's compliance its row determines it.)
    if !counts || k.gap.v.is_nan() || (compliance == 0.0 && !moves_free(&k.b, &codes, free)) {
        return (linearization(codes, rule, &k.gap, None, false), None);
    }
    let mut fe = vec![0.0; mm];
    let mut ke = vec![0.0; mm * mm];
    for i in 0..m {
        fe[i] = -lambda * k.b[i].v;
        ke[i * mm + mm - 1] = -k.b[i].v;
        ke[(mm - 1) * mm + i] = -h.d[i];
        for j in 0..m {
            ke[i * mm + j] = -lambda * k.b[i].d[j];
        }
    }
    fe[mm - 1] = -(h.v + compliance * lambda);
    ke[(mm - 1) * mm + mm - 1] = -compliance;
    let mut friction = None;
    match &k.slip {
        Some(s) if nt > 0 => {
            // The friction force's work: r_u += Σ_k λ_T,k share_k.
            for (t, share) in lambda_t.iter().zip(&s.share) {
                for i in 0..m {
                    fe[i] += t * share[i].v;
                    for j in 0..m {
                        ke[i * mm + j] += t * share[i].d[j];
                    }
                }
            }
            for (c, share) in s.share.iter().enumerate() {
                for i in 0..m {
                    ke[i * mm + m + c] = share[i].v;
                }
            }
            let (rows, stick, force) = coulomb(s, lambda, &lambda_t[..nt], m);
            for (c, row) in rows.iter().enumerate() {
                if moves_free(&s.share[c], &codes, free) {
                    fe[m + c] = row.v;
                    ke[(m + c) * mm..(m + c + 1) * mm].copy_from_slice(&row.d);
                } else {
                    fe[m + c] = lambda_t[c];
                    ke[(m + c) * mm + m + c] = 1.0;
                }
            }
            friction = Some((stick, force));
        }
        // No anchor yet (no history): the friction force is held at zero.
        _ => {
            for c in 0..nt {
                fe[m + c] = lambda_t[c];
                ke[(m + c) * mm + m + c] = 1.0;
            }
        }
    }
    let active = lambda - c * (h.v + compliance * lambda) > -c * laws.gap_tol;
    let friction = friction.filter(|_| active);
    (
        linearization(codes, rule, &h, Some((fe, ke)), active),
        friction,
    )
}

/// Whether a force spread over the displacement `codes` as `share` moves a free unknown by more
/// than round-off (1e-9 of its largest entry): shares of 1e-22 on a held node's neighbours (a
/// dual basis biorthogonal in the reference configuration) move nothing.
fn moves_free(share: &[Jet], codes: &[usize], free: &dyn Fn(usize) -> bool) -> bool {
    let size = share.iter().fold(0.0, |a: f64, x| a.max(x.v.abs()));
    share
        .iter()
        .zip(codes)
        .any(|(x, &c)| x.v.abs() > 1e-9 * size && free(c))
}

/// The rows C_T of the friction multipliers over (q, λ_T, λ) (m + nt + 1 unknowns), whether the
/// point sticks, and |P λ_T|. Evaluated in duals over z = (x_s − x_a, n, λ, λ_T) and chained.
fn coulomb(s: &SlipKinematics, lambda: f64, lambda_t: &[f64], m: usize) -> (Vec<Jet>, bool, f64) {
    let dim = lambda_t.len();
    let nz = 3 * dim + 1;
    let zero = Dual::constant(0.0, nz);
    let d: Vec<Dual> = (0..dim)
        .map(|i| Dual::variable(s.slip[i].v, i, nz))
        .collect();
    let nu: Vec<Dual> = (0..dim)
        .map(|i| Dual::variable(s.normal[i].v, dim + i, nz))
        .collect();
    let ln = Dual::variable(lambda, 2 * dim, nz);
    let lt: Vec<Dual> = (0..dim)
        .map(|i| Dual::variable(lambda_t[i], 2 * dim + 1 + i, nz))
        .collect();
    let len = nu.iter().fold(zero, |a, &v| a + v * v).sqrt();
    let n: Vec<Dual> = nu.iter().map(|&v| v / len).collect();
    let tangential = |x: &[Dual]| -> Vec<Dual> {
        let xn = (0..dim).fold(zero, |a, i| a + x[i] * n[i]);
        (0..dim).map(|i| x[i] - n[i] * xn).collect()
    };
    let gt = tangential(&d);
    let pt = tangential(&lt);
    let compliance_t = s.compliance;
    let c = capped(s.stiffness, compliance_t);
    let v: Vec<Dual> = (0..dim)
        .map(|i| pt[i] + (gt[i] - pt[i] * compliance_t) * c)
        .collect();
    let norm = v.iter().fold(zero, |a, &x| a + x * x).sqrt();
    // The slip limit μ⟨λ⟩ (its derivative taken on the λ ≥ 0 side at λ = 0).
    let limit = if ln.v >= 0.0 { ln * s.mu } else { zero };
    // On the limit (within 1e-9: a node that slid in the last step starts the next one there)
    // the point slides: the force is the same either way, and the slip branch lets a steady
    // slide go on in one iteration per step. Where v is round-off of the point's motion (a
    // repeated self-contact pair on a symmetric fold: its mean relative slip cancels to 1e-17),
    // its direction is noise: the point sticks (closing with λ = 0, the slip branch pushed it
    // with μλ along that noise, and the fold's walls slid apart).
    let motion = d.iter().fold(0.0, |a, x| a + x.v * x.v).sqrt();
    let stick = norm.v <= 1e-12 * c * motion || norm.v < limit.v * (1.0 - 1e-9);
    let proj: Vec<Dual> = if stick {
        v
    } else {
        let scale = limit / norm;
        v.iter().map(|&x| x * scale).collect()
    };
    let rows: Vec<Dual> = (0..dim).map(|i| (lt[i] - proj[i]) * (1.0 / c)).collect();
    // ∂z/∂(q, λ_T, λ): the codes are the m displacements, λ_T, then λ.
    let mm = m + dim + 1;
    let mut dz: Vec<Vec<(usize, f64)>> = Vec::with_capacity(nz);
    for jets in [&s.slip, &s.normal] {
        for j in jets.iter().take(dim) {
            dz.push(j.d.iter().copied().enumerate().collect());
        }
    }
    dz.push(vec![(mm - 1, 1.0)]);
    dz.extend((0..dim).map(|i| vec![(m + i, 1.0)]));
    let force = pt.iter().map(|x| x.v * x.v).sum::<f64>().sqrt();
    (
        rows.iter().map(|r| Jet::chain(r, &dz, mm)).collect(),
        stick,
        force,
    )
}
