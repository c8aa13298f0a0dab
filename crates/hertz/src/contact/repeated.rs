//! Self-contact's repeated pairs, shared by node-to-segment and mortar: where node a of a
//! self-contact surface meets it at (nearly) the place of node b and b meets it near a — the
//! two walls of a tube folded flat, matched node for node — the two constraints hold the same
//! motion. Two multipliers cannot share it (the constraints are dependent or nearly so), and
//! dropping one breaks the symmetry a fold has. So the two are merged into one constraint on
//! the mean gap ḡ = (g_a + g_b)/2 = 0 whose force λ acts along the mean direction
//! (B_a + B_b)/2: for a matched pair (g_a = g_b) it is either constraint, exactly; otherwise both
//! nodes meet the other wall to second order, alike. Each node of the pair reports the force
//! the merged constraint puts on it (λ times its share of the direction): the same as its
//! mirror's on a symmetric fold, the half model's on its plane.
//!
//! With friction the pair's friction force acts on its mean relative slip: a's slip over b's
//! wall and b's over a's are opposite for a matched pair, so the merged slip is
//! (s_a − s_b)/2 and a unit friction force acts along +e on a's side and −e on b's
//! ((share_a − share_b)/2), the normal (n_a − n_b)/2.

use super::dual::Jet;
use super::formulation::Local;
use super::law::{SlipKinematics, SlotKinematics};

/// A pair closer than this fraction of the spacing of the nodes around it repeats one contact;
/// a pair that was one at the previous state stays one up to `KEEP` (a band: no alternation).
pub(crate) const PAIR: f64 = 0.25;
pub(crate) const KEEP: f64 = 1.0 / 3.0;

/// How deep a node of a repeated pair may lie behind the other wall, beyond its partner's own
/// overlap, as a fraction of its spacing: where both nodes meet the other wall near the other
/// node, the one constraint holds both to second order (on walls whose nodes do not match, at
/// most 2.4 % of an element).
pub(crate) const UNHELD: f64 = 0.05;

/// How deep a node of a pair held by one constraint lies behind the other wall (`gap`, its
/// partner's `other`), if more than [`UNHELD`] of its `spacing` beyond its partner's overlap:
/// the pair is then not one contact seen from both sides — a convex corner pressed into a face
/// beside the face's node, the corner behind the face and the face's node in front of the
/// corner, or two surfaces crossing between their nodes — and the mean gap (or the kept one)
/// hides the overlap. Reported, not hidden: node-to-segment cannot hold both constraints there
/// (nearly dependent, they chatter).
pub(crate) fn unheld(gap: f64, other: f64, spacing: f64, tol: f64) -> Option<f64> {
    (gap < other.min(0.0) - (UNHELD * spacing).max(tol)).then_some(-gap)
}

/// Two nodes at one place whose partner surfaces bend by more than this apart
/// ([`crate::contact::formulation::SlotState::bend`]: a corner on a face, the face's node
/// meeting the corner) do not hold one contact seen from both sides: the one meeting the
/// flatter surface holds it, the other's constraint is dropped (their mean let the corner sink
/// into the face by the order of their offset).
pub(crate) const BEND_APART: f64 = 0.05;

/// How far apart two nodes at `xa` and `xb` lie as a pair: each from the other's contact point
/// (`pa`, `pb`), along the walls, so that a pair closing from across an open gap is one before
/// it closes (its two constraints closing in one step were dependent, the tangent singular);
/// the nodes' distance where a contact point is not known.
pub(crate) fn apart(
    xa: &[f64; 3],
    pa: Option<[f64; 3]>,
    xb: &[f64; 3],
    pb: Option<[f64; 3]>,
) -> f64 {
    let dist =
        |a: &[f64; 3], b: &[f64; 3]| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
    match (pa, pb) {
        (Some(pa), Some(pb)) => dist(&pa, xb).max(dist(&pb, xa)),
        _ => dist(xa, xb),
    }
}

/// The pairs (i, j) of `candidates` (distance, i, j) closest first, each of the `n` slots in one
/// pair at most.
pub(crate) fn closest_first(
    mut candidates: Vec<(f64, usize, usize)>,
    n: usize,
) -> Vec<(usize, usize)> {
    candidates.sort_by(|p, q| p.0.total_cmp(&q.0).then((p.1, p.2).cmp(&(q.1, q.2))));
    let mut used = vec![false; n];
    let mut out = Vec::new();
    for (_, i, j) in candidates {
        if !used[i] && !used[j] {
            used[i] = true;
            used[j] = true;
            out.push((i, j));
        }
    }
    out
}

/// A jet over another local set's unknowns, placed by `map` among `m` unknowns.
fn placed(x: &Jet, map: &[usize], m: usize) -> Jet {
    let mut d = vec![0.0; m];
    for (k, v) in x.d.iter().enumerate() {
        d[map[k]] += v;
    }
    Jet { v: x.v, d }
}

/// (x + sign·y)/2: the mean, or half the difference.
fn half_sum(x: &Jet, y: &Jet, sign: f64) -> Jet {
    Jet {
        v: 0.5 * (x.v + sign * y.v),
        d: x.d
            .iter()
            .zip(&y.d)
            .map(|(p, q)| 0.5 * (p + sign * q))
            .collect(),
    }
}

/// `sign`·½·`v` (a residual over one side's local unknowns, `map` placing it among `m`) added
/// to `out`.
fn add_half(out: &mut [Jet], v: &[Jet], map: &[usize], m: usize, sign: f64) {
    for (k, x) in v.iter().enumerate() {
        let x = placed(x, map, m);
        let t = &mut out[map[k]];
        t.v += 0.5 * sign * x.v;
        for (p, q) in t.d.iter_mut().zip(&x.d) {
            *p += 0.5 * sign * q;
        }
    }
}

/// The constraint on the mean gap of two kinematics over their local sets, over the union of
/// the sets (the first's area; neither has an open end's ramp), with friction on their mean
/// relative slip where both have friction (the first's law and anchors).
pub(crate) fn merge(
    (la, ka): (&Local, &SlotKinematics),
    (lb, kb): (&Local, &SlotKinematics),
) -> (Local, SlotKinematics) {
    let (local, map_b) = la.union(lb);
    let m = local.m();
    let map_a: Vec<usize> = (0..la.m()).collect();
    let both = |x: &Jet, y: &Jet| half_sum(&placed(x, &map_a, m), &placed(y, &map_b, m), 1.0);
    let mut b = vec![Jet::constant(0.0, m); m];
    add_half(&mut b, &ka.b, &map_a, m, 1.0);
    add_half(&mut b, &kb.b, &map_b, m, 1.0);
    let apart = |x: &Jet, y: &Jet| half_sum(&placed(x, &map_a, m), &placed(y, &map_b, m), -1.0);
    let slip = ka.slip.as_ref().zip(kb.slip.as_ref()).map(|(sa, sb)| {
        let share = (sa.share.iter().zip(&sb.share))
            .map(|(a, b)| {
                let mut v = vec![Jet::constant(0.0, m); m];
                add_half(&mut v, a, &map_a, m, 1.0);
                add_half(&mut v, b, &map_b, m, -1.0);
                v
            })
            .collect();
        SlipKinematics {
            slip: (sa.slip.iter().zip(&sb.slip))
                .map(|(x, y)| apart(x, y))
                .collect(),
            normal: (sa.normal.iter().zip(&sb.normal))
                .map(|(x, y)| apart(x, y))
                .collect(),
            share,
            mu: sa.mu,
            stiffness: sa.stiffness,
            kept: sa.kept,
            compliance: sa.compliance,
            slid: sa.slid,
        }
    });
    let kin = SlotKinematics {
        gap: both(&ka.gap, &kb.gap),
        weight: both(&ka.weight, &kb.weight),
        b,
        area: ka.area,
        past_end: None,
        slip,
    };
    (local, kin)
}

/// The size of the force a unit normal force of the kinematics `kin` (over `local`) puts on
/// `node`: |B| over the node's unknowns.
pub(crate) fn share_at(local: &Local, kin: &SlotKinematics, node: usize) -> f64 {
    let (dim, k) = (local.dim, local.index(node));
    (0..dim)
        .map(|i| kin.b[dim * k + i].v.powi(2))
        .sum::<f64>()
        .sqrt()
}
