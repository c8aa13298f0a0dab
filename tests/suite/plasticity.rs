//! Materials with a state: von Mises plasticity of bars (`MisesMat`), whose plastic strain and
//! hardening variable are committed with each converged step and restored on a cut-back.

use crate::common;

use hertz::solve::{run_analysis, SolveParams};

/// Young's modulus, hardening modulus and the three bars' yield stresses.
const E: f64 = 100.0;
const H: f64 = 10.0;
const SIG0: [f64; 3] = [1.0, 2.0, 3.0];

/// Three bars of unit length and area side by side between node 1 (held) and node 2, each of
/// its own MisesMat (yield stresses 1, 2, 3), node 2 pulled by the force history `forces`
/// (one step each) with `maxiter` Newton iterations per step.
fn three_bars(forces: &[f64], maxiter: usize) -> String {
    let t: Vec<String> = (0..=forces.len()).map(|i| i.to_string()).collect();
    let f: Vec<String> = std::iter::once(0.0)
        .chain(forces.iter().copied())
        .map(|v| v.to_string())
        .collect();
    let mut s = format!(
        "bars.out\nthree bars yielding one after the other\n\
         StaticStructural nsteps {} rtolf 1e-12 maxiter {maxiter} manrmsteps 1\n\
         domain 1dTruss\nOutputManager\n\
         ndofman 2 nelem 3 ncrosssect 1 nmat 3 nbc 2 nic 0 nltf 1 nset 2\n\
         node 1 coords 1 0\nnode 2 coords 1 1\n",
        forces.len()
    );
    for e in 1..=3 {
        s += &format!("Truss1d {e} nodes 2 1 2 crossSect 1 mat {e}\n");
    }
    s += "SimpleCS 1 area 1\n";
    for (m, sig0) in SIG0.iter().enumerate() {
        s += &format!(
            "MisesMat {} d 0 E {E} n 0.3 sig0 {sig0} H {H} tAlpha 0\n",
            m + 1
        );
    }
    s += "BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 1\n";
    s += "NodalLoad 2 loadTimeFunction 1 dofs 1 1 components 1 1 set 2\n";
    s += &format!(
        "PiecewiseLinFunction 1 npoints {} t {} {} f(t) {} {}\n",
        t.len(),
        t.len(),
        t.join(" "),
        f.len(),
        f.join(" ")
    );
    s += "Set 1 nodes 1 1\nSet 2 nodes 1 2\n";
    s
}

/// Displacement of node 2 and substeps, per step.
fn solve(text: &str) -> Vec<(f64, usize)> {
    let model = common::model_from_text(text).unwrap();
    let mut out = Vec::new();
    run_analysis(&model, &SolveParams::default(), |r| {
        out.push((r.displacement(1, 1).unwrap(), r.info.substeps));
        Ok(())
    })
    .unwrap();
    out
}

/// The exact response: the force of the three bars at a monotonically reached strain ε.
fn force_at(eps: f64) -> f64 {
    SIG0.iter()
        .map(|&s0| {
            let ey = s0 / E;
            if eps <= ey {
                E * eps
            } else {
                s0 + E * H / (E + H) * (eps - ey)
            }
        })
        .sum()
}

/// Loaded to 8 (every bar yields: ε = 0.28/3 exactly), unloaded to 0 (elastically, E·3 = 300:
/// a residual strain 0.28/3 − 8/300), reloaded to 8 (elastically back to the same strain).
#[test]
fn bars_yield_harden_and_keep_their_plastic_strain_after_unloading() {
    let steps = solve(&three_bars(&[2.0, 5.0, 8.0, 0.0, 8.0], 25));
    let peak = 0.28 / 3.0;
    assert!((force_at(peak) - 8.0).abs() < 1e-12);
    let expected = [2.0 / 300.0, 0.0, peak, peak - 8.0 / 300.0, peak];
    // Step 2 (F = 5): bar 1 has yielded, bars 2 and 3 not: 1 + 100/11 (ε − 0.01) + 200 ε = 5
    // (E·H/(E + H) = 100/11).
    let eps5 = (5.0 - 1.0 + 100.0 / 11.0 * 0.01) / (100.0 / 11.0 + 200.0);
    assert!((force_at(eps5) - 5.0).abs() < 1e-12);
    let expected = [expected[0], eps5, expected[2], expected[3], expected[4]];
    for (k, ((u, _), want)) in steps.iter().zip(expected).enumerate() {
        assert!(
            (u - want).abs() < 1e-12,
            "step {}: u {u}, exact {want}",
            k + 1
        );
    }
}

/// Loaded to 8, then to −12 in one step: the bars unload and yield in compression. With two
/// Newton iterations per step, that step is cut back, and so are its halves: substeps that
/// converge before a failing one (the bars yielding back) commit their plastic strains, which
/// the retry must roll back to the step's start, or the bars would start the retry yielded
/// backwards, yield forwards again and harden more. The answer equals the run without
/// cut-backs.
#[test]
fn a_cut_back_restores_the_committed_plastic_state() {
    let reference = solve(&three_bars(&[8.0, -12.0], 25));
    assert!(reference.iter().all(|&(_, n)| n == 1), "{reference:?}");
    let cut = solve(&three_bars(&[8.0, -12.0], 2));
    assert!(
        cut[1].1 >= 8,
        "the reversal is cut back three times: {cut:?}"
    );
    for (k, (a, b)) in cut.iter().zip(&reference).enumerate() {
        assert!(
            (a.0 - b.0).abs() < 1e-12,
            "step {}: {} with cut-backs, {} without",
            k + 1,
            a.0,
            b.0
        );
    }
    assert!((reference[0].0 - 0.28 / 3.0).abs() < 1e-12);
}

/// Plastic continua: a steel-like `MisesMat` (E 210, ν 0.3, σ₀ 0.3, H 10).
fn steel(kinematic: f64) -> hertz::model::Mises {
    hardened(kinematic, 10.0)
}

/// [`steel`] with isotropic hardening modulus `modulus` (0: perfectly plastic).
fn hardened(kinematic: f64, modulus: f64) -> hertz::model::Mises {
    hertz::model::Mises {
        young: 210.0,
        poisson: 0.3,
        hardening: hertz::model::Hardening::Linear { sig0: 0.3, modulus },
        kinematic,
        damage: None,
    }
}

/// The tangent of every continuum element with `MisesMat` is the Jacobian of its internal force,
/// from a committed plastic state, in a step that yields further (plastic) and one that unloads
/// (elastic), in small strain (isotropic and kinematic hardening, and none: perfectly plastic)
/// and finite strain (hardening and none), plain and barred.
#[test]
fn plastic_continuum_tangents_are_jacobians_of_the_internal_force() {
    use hertz::fem::rule;
    use hertz::material::plasticity::mises_law;
    use hertz::solid::ContinuumKernel;
    for (name, shape, mode, nip) in crate::elements::CONTINUUM {
        let barrable = matches!(name, "Quad1PlaneStrain" | "LSpace");
        let cases = [
            (false, 0.0, 10.0, false),
            (false, 8.0, 10.0, false),
            (true, 0.0, 10.0, false),
            (false, 0.0, 0.0, false),
            (true, 0.0, 0.0, false),
            (false, 0.0, 0.0, true),
            (true, 0.0, 0.0, true),
        ];
        for (nlgeo, kinematic, modulus, bbar) in cases {
            if bbar && !barrable {
                continue;
            }
            let law = mises_law(&hardened(kinematic, modulus), mode, nlgeo);
            let q = rule(shape, nip).unwrap();
            let k = ContinuumKernel {
                shape,
                nsd: shape.dim(),
                rule: &q,
                material: law.as_ref(),
                thick: 0.7,
                nlgeo,
                bbar,
                hoop: None,
            };
            let x = crate::elements::distorted_nodes(shape);
            let nd = shape.n_nodes() * shape.dim();
            // A plastic first step, committed.
            let u1: Vec<f64> = (0..nd)
                .map(|i| 0.02 * ((i as f64 * 0.9 + 0.3).sin()))
                .collect();
            let (virgin, old) =
                crate::elements::first_step_state(&k, law.as_ref(), q.len(), &x, &u1);
            assert!(old != virgin, "{name}: the first step yields");
            for (what, factor) in [("plastic", 1.5), ("elastic", 0.97)] {
                let u: Vec<f64> = u1.iter().map(|v| v * factor).collect();
                let worst = crate::elements::tangent_error(&k, &x, &u, &old, 1e-8);
                assert!(
                    worst < 1e-6,
                    "{name} nlgeo {nlgeo} hk {kinematic} H {modulus} bbar {bbar} {what}: \
                     relative tangent error {worst:e}"
                );
            }
        }
    }
}

/// A brick deformed plastically in large deformation, then turned rigidly by 90°: its second
/// Piola–Kirchhoff stress, plastic strain and κ stay what they were, and its nodal forces turn
/// with it.
#[test]
fn a_plastic_brick_turned_rigidly_keeps_its_stress_and_plastic_state() {
    use hertz::fem::{rule, Shape};
    use hertz::material::plasticity::mises_law;
    use hertz::model::StressMode;
    use hertz::solid::{ContinuumKernel, ElementKernel, GpState};
    let shape = Shape::Hexa8;
    let law = mises_law(&steel(0.0), StressMode::ThreeD, true);
    let q = rule(shape, 8).unwrap();
    let k = ContinuumKernel {
        shape,
        nsd: 3,
        rule: &q,
        material: law.as_ref(),
        thick: 1.0,
        nlgeo: true,
        bbar: false,
        hoop: None,
    };
    let x = crate::elements::distorted_nodes(shape);
    let n = law.state_len();
    let mut virgin = vec![0.0; n * q.len()];
    for g in 0..q.len() {
        law.initial_state(&mut virgin[g * n..(g + 1) * n]);
    }
    // Stretch along x, shear in xy: plastic through the brick.
    let u: Vec<f64> = x
        .iter()
        .flat_map(|p| [0.2 * p[0] + 0.1 * p[1], -0.05 * p[1], -0.05 * p[2]])
        .collect();
    let (mut committed, mut f, mut states) = (vec![0.0; virgin.len()], vec![0.0; 24], Vec::new());
    k.evaluate_into(
        &x,
        &u,
        (&virgin, &mut committed),
        &mut f,
        None,
        Some(&mut states),
    )
    .unwrap();
    assert!(states
        .iter()
        .all(|s: &GpState| s.plastic.unwrap().kappa > 1e-3));
    // The deformed position x + u turned by 90° about z (and moved): u' = R(X + u) + c − X.
    let turned: Vec<f64> = (0..8)
        .flat_map(|a| {
            let p = [
                x[a][0] + u[3 * a],
                x[a][1] + u[3 * a + 1],
                x[a][2] + u[3 * a + 2],
            ];
            [
                -p[1] + 3.0 - x[a][0],
                p[0] - 1.0 - x[a][1],
                p[2] + 0.5 - x[a][2],
            ]
        })
        .collect();
    // The same step again from the same committed state, turned: the same answer.
    let (mut again, mut f2, mut states2) = (vec![0.0; virgin.len()], vec![0.0; 24], Vec::new());
    k.evaluate_into(
        &x,
        &turned,
        (&virgin, &mut again),
        &mut f2,
        None,
        Some(&mut states2),
    )
    .unwrap();
    for (a, b) in states.iter().zip(&states2) {
        let (pa, pb) = (a.plastic.unwrap(), b.plastic.unwrap());
        assert!(
            (pa.kappa - pb.kappa).abs() < 1e-12,
            "κ {} against {}",
            pb.kappa,
            pa.kappa
        );
        for i in 0..6 {
            assert!(
                (a.stress[i] - b.stress[i]).abs() < 1e-11,
                "S {:?} against {:?}",
                b.stress,
                a.stress
            );
            assert!((pa.strain[i] - pb.strain[i]).abs() < 1e-12);
        }
    }
    for (a, b) in committed.iter().zip(&again) {
        assert!(
            (a - b).abs() < 1e-12,
            "state {again:?} against {committed:?}"
        );
    }
    for node in 0..8 {
        let (fx, fy, fz) = (f[3 * node], f[3 * node + 1], f[3 * node + 2]);
        let turned_f = [-fy, fx, fz];
        for i in 0..3 {
            assert!(
                (f2[3 * node + i] - turned_f[i]).abs() < 1e-11,
                "node {node}: {:?}",
                &f2[3 * node..3 * node + 3]
            );
        }
    }
}

/// A plate (9 × 4, four elements of `kind` with a node inside, or two quadrilaterals) pushed
/// past yield by a force: uniaxial stress −P/4 at every integration point, exact, with the
/// plastic strain of the closed form, in plane stress and plane strain. Full Newton (hertz's
/// choice for a yielding material where OOFEM keeps the first tangent) converges in a handful
/// of iterations.
#[test]
fn a_plastic_patch_under_uniaxial_force_is_exact_in_every_plane_element() {
    let (e, nu, s0, h, p) = (15.0, 0.25, 1.0, 0.5, 5.0);
    for (kind, plane_strain) in [
        ("TrPlaneStress2d", false),
        ("TrPlaneStrain", true),
        ("PlaneStress2d", false),
        ("Quad1PlaneStrain", true),
    ] {
        let triangles = kind.starts_with("Tr");
        let elements = if triangles {
            format!(
                "{kind} 1 nodes 3 1 3 2\n{kind} 2 nodes 3 1 4 3\n{kind} 3 nodes 3 3 5 2\n\
                 {kind} 4 nodes 3 3 4 5\n"
            )
        } else {
            format!("{kind} 1 nodes 4 1 3 6 2\n{kind} 2 nodes 4 3 4 5 6\n")
        };
        let nelem = if triangles { 4 } else { 2 };
        let text = format!(
            "plastic.out\nplastic patch\nStaticStructural nsteps 2 rtolf 1e-10 maxiter 10\n\
             domain {}\nOutputManager\n\
             ndofman 6 nelem {nelem} ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 1 nset 4\n\
             Node 1 coords 3 0 0 0\nNode 2 coords 3 0 4 0\nNode 3 coords 3 3 1 0\n\
             Node 4 coords 3 9 0 0\nNode 5 coords 3 9 4 0\nNode 6 coords 3 4 4 0\n\
             {elements}SimpleCS 1 thick 1.0 material 1 set 1\n\
             MisesMat 1 d 0 E {e} n {nu} sig0 {s0} H {h} tAlpha 0\n\
             BoundaryCondition 1 loadTimeFunction 1 dofs 1 2 values 1 0.0 set 4\n\
             BoundaryCondition 2 loadTimeFunction 1 dofs 1 1 values 1 0.0 set 2\n\
             NodalLoad 3 loadTimeFunction 1 dofs 2 1 2 Components 2 {} 0.0 set 3\n\
             PiecewiseLinFunction 1 npoints 3 t 3 0 1 2 f(t) 3 0 0.5 1\n\
             Set 1 elementranges {{(1 {nelem})}}\nSet 2 nodes 2 1 2\nSet 3 nodes 2 4 5\n\
             Set 4 nodes 1 1\n",
            if plane_strain {
                "PlaneStrain"
            } else {
                "2dPlaneStress"
            },
            -p / 2.0
        );
        // Node 6 is the top's second node for quadrilaterals; triangles leave it loose.
        let text = if triangles {
            text.replace("ndofman 6", "ndofman 5")
                .replace("Node 6 coords 3 4 4 0\n", "")
        } else {
            text.replace("Node 3 coords 3 3 1 0", "Node 3 coords 3 4 0 0")
        };
        let model = common::model_from_text(&text).unwrap();
        let sigma = -p / 4.0;
        run_analysis(&model, &SolveParams::default(), |r| {
            assert!(
                r.info.iterations <= 6,
                "{kind}: {} iterations",
                r.info.iterations
            );
            if r.step == 2 {
                for g in r.states.iter().flatten() {
                    let pl = g.plastic.unwrap();
                    // Plane stress: σ = (σ, 0, 0); plane strain σ_zz follows from ε_zz = 0.
                    assert!(
                        (g.stress[0] - sigma).abs() < 1e-9,
                        "{kind}: σ {:?}",
                        g.stress
                    );
                    assert!(g.stress[1].abs() < 1e-9 && g.stress[5].abs() < 1e-9);
                    if !plane_strain {
                        let kappa = (sigma.abs() - s0) / h;
                        assert!((pl.kappa - kappa).abs() < 1e-9, "{kind}: κ {}", pl.kappa);
                        let exx = sigma / e - kappa;
                        assert!((g.strain[0] - exx).abs() < 1e-9, "{kind}: ε {:?}", g.strain);
                        let eyy = -nu * sigma / e + 0.5 * kappa;
                        assert!((g.strain[1] - eyy).abs() < 1e-9, "{kind}: ε {:?}", g.strain);
                        assert!(
                            (g.strain[2] - eyy).abs() < 1e-9,
                            "{kind}: ε_zz {:?}",
                            g.strain
                        );
                    } else {
                        // σ_zz between 0 and ν·σ_xx, the plastic strain isochoric.
                        let pe = pl.strain;
                        assert!((pe[0] + pe[1] + pe[2]).abs() < 1e-12, "{kind}: ε_p {pe:?}");
                        assert!(pl.kappa > 0.0, "{kind} yields");
                    }
                }
            }
            Ok(())
        })
        .unwrap();
    }
}
