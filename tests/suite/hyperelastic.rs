//! Hyperelastic materials through the whole program (reader, kernel, Newton): homogeneous
//! deformations of one brick against the closed forms of upstream OOFEM's spec (§4.5).
//! * Confined stretch F = diag(1.2, 1, 1) (every DOF prescribed): P11 and P22 of each law.
//! * Free uniaxial stress (rollers on three faces, the x = 1 face moved by 0.2): the lateral
//!   stretch λt and the axial force P11 = reaction over the unit area, quadratic Newton.

use crate::common;

use hertz::fem::shape::HEXA8_CORNERS;
use hertz::solve::run_analysis;

/// The laws with spec-upstream §4.5's figures at λ = 1.2: (record, confined P11, P22, free λt,
/// free P11).
const LAWS: [(&str, f64, f64, f64, f64); 3] = [
    (
        "mooneyrivlincompressiblemat 1 d 0 c1 1 c2 0.5 k 10",
        2.143974,
        1.448439,
        0.936727,
        1.289864,
    ),
    (
        "ogdencompressiblemat 1 d 0 alpha 2 1.3 -2 mu 2 0.8 -0.4 k 10",
        1.705866,
        1.711304,
        0.920361,
        0.408560,
    ),
    (
        "simopistermat 1 d 0 g 1 k 10",
        1.886013,
        1.823216,
        0.919916,
        0.494796,
    ),
];

/// A unit brick with `nlgeo 1`, the material record `mat` and boundary conditions `bcs` (sets:
/// 1 all elements, 2 the x = 0 nodes, 3 y = 0, 4 z = 0, 5 x = 1, 6 all nodes).
fn brick(mat: &str, bcs: &[String]) -> String {
    let mut s = format!(
        "hyper.out\nhyperelastic brick\nNonLinearStatic nsteps 1 controlmode 1 rtolf 1e-12 maxiter 20 manrmsteps 1\n\
         domain 3d\nOutputManager\n\
         ndofman 8 nelem 1 ncrosssect 1 nmat 1 nbc {} nic 0 nltf 1 nset 6\n",
        bcs.len()
    );
    for (i, p) in HEXA8_CORNERS.iter().enumerate() {
        s += &format!("node {} coords 3 {} {} {}\n", i + 1, p[0], p[1], p[2]);
    }
    s += "LSpace 1 nodes 8 1 2 3 4 5 6 7 8 nlgeo 1\nSimpleCS 1 material 1 set 1\n";
    s += mat;
    s.push('\n');
    for b in bcs {
        s += b;
        s.push('\n');
    }
    s += "ConstantFunction 1 f(t) 1\nSet 1 allelements\n";
    let on = |axis: usize, v: usize| -> Vec<String> {
        HEXA8_CORNERS
            .iter()
            .enumerate()
            .filter(|(_, c)| c[axis] == v)
            .map(|(i, _)| (i + 1).to_string())
            .collect()
    };
    for (k, (axis, v)) in [(0, 0), (1, 0), (2, 0), (0, 1)].iter().enumerate() {
        let ids = on(*axis, *v);
        s += &format!("Set {} nodes {} {}\n", k + 2, ids.len(), ids.join(" "));
    }
    s += "Set 6 nodes 8 1 2 3 4 5 6 7 8\n";
    s
}

#[test]
fn confined_stretch_gives_the_closed_form_stresses() {
    for (mat, p11, p22, _, _) in LAWS {
        // u_x = 0.2 x on every node, u_y = u_z = 0.
        let bcs = vec![
            "BoundaryCondition 1 loadTimeFunction 1 dofs 3 1 2 3 values 3 0 0 0 set 6".to_string(),
            "BoundaryCondition 2 loadTimeFunction 1 dofs 3 1 2 3 values 3 0.2 0 0 set 5"
                .to_string(),
        ];
        let model = common::model_from_text(&brick(mat, &bcs)).unwrap();
        let mut seen = 0;
        run_analysis(&model, &common::quiet(), |r| {
            for gp in &r.states[0] {
                assert!((gp.p[0][0] - p11).abs() < 5e-6, "{mat}: P11 {}", gp.p[0][0]);
                assert!((gp.p[1][1] - p22).abs() < 5e-6, "{mat}: P22 {}", gp.p[1][1]);
                assert!((gp.p[2][2] - p22).abs() < 5e-6, "{mat}: P33 {}", gp.p[2][2]);
                seen += 1;
            }
            Ok(())
        })
        .unwrap();
        assert_eq!(seen, 8);
    }
}

#[test]
fn free_uniaxial_stress_gives_the_closed_form_lateral_stretch_and_force() {
    for (mat, _, _, lt, p11) in LAWS {
        let bcs = vec![
            "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2".to_string(),
            "BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 3".to_string(),
            "BoundaryCondition 3 loadTimeFunction 1 dofs 1 3 values 1 0 set 4".to_string(),
            "BoundaryCondition 4 loadTimeFunction 1 dofs 1 1 values 1 0.2 set 5".to_string(),
        ];
        let model = common::model_from_text(&brick(mat, &bcs)).unwrap();
        let mut checked = false;
        run_analysis(&model, &common::quiet(), |r| {
            // Lateral stretch: the y = 1 nodes moved by λt − 1.
            for (i, c) in HEXA8_CORNERS.iter().enumerate() {
                if c[1] == 1 {
                    let v = r.displacement(i, 2).unwrap();
                    assert!((v - (lt - 1.0)).abs() < 2e-6, "{mat}: λt {}", 1.0 + v);
                }
            }
            // Axial force: the reactions of the x = 1 face, over the unit reference area.
            let f: f64 = r
                .dofs
                .prescribed
                .iter()
                .zip(r.reactions)
                .filter(|((n, d, _), _)| *d == 1 && HEXA8_CORNERS[*n][0] == 1)
                .map(|(_, &v)| v)
                .sum();
            assert!((f - p11).abs() < 2e-6, "{mat}: P11 {f}");
            // Newton converges quadratically to 1e-12 in a few iterations.
            assert!(
                r.info.iterations <= 6,
                "{mat}: {:?}",
                r.info.residual_history
            );
            checked = true;
            Ok(())
        })
        .unwrap();
        assert!(checked);
    }
}
