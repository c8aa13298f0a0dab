//! A contact model moved far from the origin (a mesh in a machine's coordinates) is solved as at
//! the origin: the same contact, the same forces to the round-off of its positions, about the
//! same Newton iterations.

use crate::common::{model_from_text, quiet};

/// `text` with every node and every rigid segment's reference point moved by `d` along each
/// axis.
fn moved(text: &str, d: f64) -> String {
    let shift = |tokens: &mut Vec<String>, key: &str| {
        if let Some(i) = tokens.iter().position(|t| t.eq_ignore_ascii_case(key)) {
            let n: usize = tokens[i + 1].parse().unwrap();
            for t in &mut tokens[i + 2..i + 2 + n] {
                *t = format!("{:e}", t.parse::<f64>().unwrap() + d);
            }
        }
    };
    let mut out = String::new();
    for line in text.lines() {
        let lower = line.trim_start().to_lowercase();
        let mut tokens: Vec<String> = line.split_whitespace().map(String::from).collect();
        if lower.starts_with("node ") {
            shift(&mut tokens, "coords");
        } else if lower.contains("contactsegment") {
            shift(&mut tokens, "point");
            shift(&mut tokens, "centerpoint");
        } else {
            out += line;
            out.push('\n');
            continue;
        }
        out += &tokens.join(" ");
        out.push('\n');
    }
    out
}

/// The last step's total contact force, the Newton iterations of all steps and the steps.
fn solve(text: &str) -> (f64, usize, usize) {
    let model = model_from_text(text).unwrap();
    let (mut force, mut iterations, mut steps) = (0.0, 0, 0);
    hertz::solve::run_analysis(&model, &quiet(), |r| {
        force = r.contact.iter().map(|s| s.force).sum();
        iterations += r.info.iterations;
        steps += 1;
        Ok(())
    })
    .unwrap_or_else(|e| panic!("{e}"));
    (force, iterations, steps)
}

/// Each example moved 10³ and 10⁵ from the origin. Before, node-to-segment and node-to-face
/// contact failed there: the projections onto edges and faces worked in absolute coordinates
/// and never settled on a surface 10⁶ of its elements away (pairs refused by turns: 3D
/// multipliers chattered, 213 iterations and 5 halvings); and the convergence test's round-off
/// floors took the gaps' round-off from the model's size, not its coordinates' (a penalty of
/// 1e7 stalled at 20 times rtolf 1e-8 from 10³ away; large-deformation multipliers at 3 times
/// rtolf 1e-12).
#[test]
fn contact_models_far_from_the_origin_are_solved_as_at_the_origin() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    // Penalty forces (1e7 here) are ε_p·g of penetrations g of about 1e-8, each known to ε·d of
    // the positions (2e-11 at d = 10⁵): to 1e-8·d of themselves. Multipliers hold g = 0: their
    // forces keep about ten digits more.
    for (file, penalty) in [
        // node-to-face multipliers (3D)
        ("cylinder3d.in", false),
        // node-to-face multipliers, large deformation (3D)
        ("patch3d.in", false),
        // node-to-segment penalty between two bodies (2D)
        ("hertz_cylinder.in", true),
        // penalty against a rigid line and a rigid circle (2D)
        ("flat_punch.in", true),
        ("hertz_rigid_circle.in", true),
        // mortar multipliers between two bodies (2D)
        ("hertz_cylinder_mortar.in", false),
    ] {
        let text = std::fs::read_to_string(root.join(file)).unwrap();
        let (force, iterations, steps) = solve(&text);
        assert!(force > 0.0, "{file}: no contact force");
        for d in [1e3, 1e5] {
            let (f, it, _) = solve(&moved(&text, d));
            let rel = (f / force - 1.0).abs();
            let tol = if penalty { 1e-8 * d } else { 1e-9 };
            assert!(rel < tol, "{file} moved {d:e}: force {f} against {force}");
            // At most two more a step: a tolerance below the positions' round-off is met
            // where Newton stops gaining on it (and a warning says so).
            assert!(
                it <= iterations + 2 * steps,
                "{file} moved {d:e}: {it} iterations against {iterations}"
            );
        }
    }
}
