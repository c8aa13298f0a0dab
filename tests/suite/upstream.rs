//! Today's upstream OOFEM contact input (contact elements, StructuralFEContactSurface,
//! StructuralPenaltyContactBC with pn, pt, friction), read and solved: the reference inputs of
//! `../shared/spec/oofem-upstream-contact.md` §5 (tests/data/upstream), against the figures the
//! upstream binary gives where it is right.

use crate::common;

use hertz::solve::run_analysis;
use std::path::Path;

fn data(name: &str) -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/upstream")
            .join(name),
    )
    .unwrap()
}

/// Per step: the summed reactions of the boundary conditions `bcs` (DOF 1, 2, 3), the contact
/// nodes' summed normal and friction forces, and the iterations.
fn solve(text: &str, bcs: &[usize]) -> Vec<([f64; 3], f64, f64, usize)> {
    let model = common::model_from_text(text).unwrap();
    let mut out = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        let mut reaction = [0.0; 3];
        for (&(_, d, b), &f) in r.dofs.prescribed.iter().zip(r.reactions) {
            if bcs.contains(&model.dirichlet[b].number) {
                reaction[d as usize - 1] += f;
            }
        }
        let normal: f64 = r.contact.iter().map(|s| s.force).sum();
        let friction: f64 = r
            .contact
            .iter()
            .filter_map(|s| s.friction)
            .map(|f| f.1)
            .sum();
        out.push((reaction, normal, friction, r.info.iterations));
        Ok(())
    })
    .unwrap();
    out
}

/// §5.2: a brick pressed 0.02 onto a base (Ogden, two-pass, frictionless): the top's reaction is
/// upstream's −137.09, in 3 iterations per step.
#[test]
fn upstream_3d_brick_on_base_gives_upstreams_reaction() {
    let steps = solve(&data("two3d.in"), &[2]);
    let rz = steps[1].0[2];
    println!(
        "3D: sum Rz(top) {rz:.4} (upstream -137.09), iterations {:?}",
        steps.iter().map(|s| s.3).collect::<Vec<_>>()
    );
    assert!((rz + 137.09).abs() < 0.005, "{rz}");
    assert!(steps.iter().all(|s| s.3 <= 4));
}

/// §5.1: a block pressed onto a base then slid (Mooney–Rivlin, two-pass, μ = 0.3): in steps 2–4
/// every slave point slides, the friction is exactly μ times the normal force, and the top's
/// reactions have the ratio upstream finds, 0.300 (the base's top surface turns a little under
/// the load, so the reactions' ratio is μ to 3 digits). The master's node order does not matter
/// (upstream finds no contact at all when the base's contact element lists its nodes clockwise).
#[test]
fn upstream_2d_block_slides_at_mu() {
    let forward = data("two2d.in");
    let reversed = forward.replace(
        "StructuralContactElement_LineLin 3 nodes 2 3 4",
        "StructuralContactElement_LineLin 3 nodes 2 4 3",
    );
    assert_ne!(forward, reversed);
    let runs = [solve(&forward, &[2, 3]), solve(&reversed, &[2, 3])];
    for (k, s) in runs[0].iter().enumerate().skip(1) {
        let (r, normal, friction, its) = *s;
        let ratio = r[0].abs() / r[1].abs();
        println!(
            "2D step {}: Rx/Ry {ratio:.5}, friction/normal {:.12}, {its} iterations",
            k + 1,
            friction / normal
        );
        assert!((ratio - 0.3).abs() < 5e-4, "{ratio}");
        assert!((friction / normal - 0.3).abs() < 1e-10);
        assert!(its <= 5);
        let other = runs[1][k];
        assert!((other.0[0] - r[0]).abs() < 1e-9 * r[0].abs(), "node order");
    }
}

/// Upstream's own test `tests/sm/contact2d.in` (a block pressed down an incline, Mooney–Rivlin,
/// two-pass, pn = 1e8): every displacement its check rules give, to their tolerance 1e-6. (Its
/// last two rule pairs name node 4 but hold nodes 5 and 6: the values are those of the block's
/// bottom corners, as hertz's and upstream's `.out` show.)
#[test]
fn upstream_contact2d_test_gives_its_checked_displacements() {
    let model = common::model_from_text(&data("contact2d.in")).unwrap();
    let expected = [
        (3, [2.10680587e-01, -1.76686565e-02]),
        (4, [1.03015750e-01, 4.44336000e-03]),
        (5, [-1.60418808e-01, -2.39980173e-01]),
        (6, [-6.69405872e-02, -2.51299903e-01]),
    ];
    let mut worst = f64::NAN;
    let mut iterations = Vec::new();
    run_analysis(&model, &common::quiet(), |r| {
        iterations.push(r.info.iterations);
        if r.step == 5 {
            worst = 0.0;
            for (label, u) in expected {
                let n = model.nodes.iter().position(|x| x.label == label).unwrap();
                for (d, want) in (1u8..).zip(u) {
                    worst = worst.max((r.displacement(n, d).unwrap() - want).abs());
                }
            }
        }
        Ok(())
    })
    .unwrap();
    println!("contact2d: worst difference {worst:.2e}, iterations {iterations:?}");
    assert!(worst < 1e-6, "{worst}");
    assert!(iterations.iter().all(|&i| i <= 6), "{iterations:?}");
}

/// §5.2 with μ = 0.3 and the top then slid by 0.1 over three steps (upstream diverges to NaN in
/// the first frictional step, QUIRK 5): every slave point slides with friction exactly μ times
/// its normal force, the top's reactions in the ratio μ to within the base's tilt under the
/// brick (2 %: the friction drags the soft base's face, whose normal tilts), in at most 6
/// iterations per step.
#[test]
fn upstream_3d_brick_slides_with_friction() {
    let steps = solve(&data("two3d_friction.in"), &[2, 6]);
    for (k, &(r, normal, friction, its)) in steps.iter().enumerate().skip(1) {
        let ratio = r[0].abs() / r[2].abs();
        println!(
            "3D slide step {}: Rx/Rz {ratio:.4}, friction/normal {:.12}, {its} iterations",
            k + 1,
            friction / normal
        );
        assert!((friction / normal - 0.3).abs() < 1e-10);
        assert!((ratio - 0.3).abs() < 0.3 * 0.02, "{ratio}");
        assert!(its <= 6, "{its}");
    }
}
