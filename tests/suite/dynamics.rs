//! Implicit dynamics (`NonLinearDynamic`): a mass on a spring against the schemes' exact
//! discrete solutions, the energy balance, a free body's translation, and an elastic rod hitting
//! a rigid wall against 1D wave theory.

use hertz::solve::{run_analysis, Energy};

/// A bar (E = 100, A = 1, L = 1, ρ = 1: a mass of ½ at its free end on a spring of 100, ω = √200)
/// fixed at node 1, node 2 started at u = 0.01 at rest; `scheme` the analysis's keywords.
fn spring(scheme: &str, nsteps: usize, dt: f64) -> String {
    format!(
        "spring.out\nmass on a spring\nNonLinearDynamic nsteps {nsteps} deltat {dt} {scheme} \
         rtolf 1e-12 manrmsteps 1\ndomain 1dTruss\nOutputManager\n\
         ndofman 2 nelem 1 ncrosssect 1 nmat 1 nbc 1 nic 1 nltf 1 nset 2\n\
         node 1 coords 1 0\nnode 2 coords 1 1\nTruss1d 1 nodes 2 1 2 crossSect 1 mat 1\n\
         SimpleCS 1 area 1 material 1 set 1\nIsoLE 1 d 1 E 100 n 0 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n\
         InitialCondition 1 conditions 1 u 0.01 set 1 dofs 1 1\nConstantFunction 1 f(t) 1\n\
         Set 1 nodes 1 2\nSet 2 nodes 1 1\n"
    )
}

/// OOFEM's `DIIDynamic` runs on NonLinearDynamic's engine: on the (linear) spring each scheme
/// gives NonLinearDynamic's steps (to 1e-15), the trapezoidal rule its exact discrete solution
/// u₀ cos(ω̄ t) (1e-13), and the `.out` blocks are OOFEM's default ones (DIIDynamic writes no
/// "Equilibrium reached" line), with d, v and a per DOF. Wilson-θ (`ddtScheme 3`) is refused at
/// its line (tests/data/bad/dii_wilson.in).
#[test]
fn dii_dynamic_is_nonlinear_dynamics_on_a_linear_model() {
    let omega = 200f64.sqrt();
    let dt = 2.0 * std::f64::consts::PI / omega / 20.0;
    for scheme in ["ddtScheme 0", "ddtScheme 1", "ddtScheme 2"] {
        let text = spring(scheme, 30, dt);
        let dii = text.replace("NonLinearDynamic", "DIIDynamic");
        let (a, b) = (history(&text), history(&dii));
        assert_eq!(a.len(), b.len());
        for ((t, u, _), (s, v, _)) in a.iter().zip(&b) {
            assert_eq!(t, s);
            assert!((u - v).abs() <= 1e-15, "{scheme}: t {t}: {u} vs {v}");
            if scheme == "ddtScheme 2" {
                let discrete = 2.0 / dt * (omega * dt / 2.0).atan();
                let exact = 0.01 * (discrete * t).cos();
                assert!((v - exact).abs() < 1e-13, "t {t}: {v} vs {exact}");
            }
        }
        let listed = dii.replace("OutputManager\n", "OutputManager tstep_all dofman_all\n");
        let model = crate::common::model_from_text(&listed).unwrap();
        let mut block = String::new();
        run_analysis(&model, &crate::common::quiet(), |r| {
            if r.step == 1 {
                block = hertz::output::outfile::step_block(&model, r).concat();
            }
            Ok(())
        })
        .unwrap();
        assert!(
            block.contains("=====\nOutput for time 2.22144147e-02")
                && !block.contains("Equilibrium"),
            "{block}"
        );
        assert!(block.contains(" v ") && block.contains(" a "), "{block}");
    }
}

/// The free end's displacement and the energies at every step.
fn history(text: &str) -> Vec<(f64, f64, Energy)> {
    let model = crate::common::model_from_text(text).unwrap();
    let mut out = Vec::new();
    run_analysis(&model, &crate::common::quiet(), |r| {
        let m = r.motion.expect("a dynamic step has its motion");
        out.push((r.time, r.displacement(1, 1).unwrap(), m.energy));
        Ok(())
    })
    .unwrap();
    out
}

/// The mechanical energy of the spring at a step: kinetic + the spring's (its work from the
/// start plus ½ k u₀²).
fn mechanical(e: &Energy) -> f64 {
    e.kinetic + e.internal + 0.5 * 100.0 * 0.01 * 0.01
}

/// The trapezoidal rule (Newmark γ = ½, β = ¼) gives u_n = u₀ cos(ω̄ t_n) with
/// tan(ω̄Δt/2) = ωΔt/2 exactly, and keeps the energy to round-off; backward Euler (`ddtScheme
/// 1`) multiplies it by 1/(1 + ω²Δt²) every step; OOFEM's default three-point scheme and Newmark
/// with γ > ½ lose energy.
#[test]
fn a_mass_on_a_spring_follows_each_schemes_discrete_solution() {
    let omega = 200f64.sqrt();
    let dt = 2.0 * std::f64::consts::PI / omega / 20.0;
    let trapezoid = history(&spring("ddtScheme 2", 60, dt));
    let discrete = 2.0 / dt * (omega * dt / 2.0).atan();
    let e0 = 0.5 * 100.0 * 1e-4;
    for (t, u, e) in &trapezoid {
        let exact = 0.01 * (discrete * t).cos();
        assert!((u - exact).abs() < 1e-13, "t {t}: {u} vs {exact}");
        assert!((mechanical(e) / e0 - 1.0).abs() < 1e-12, "t {t}: {e:?}");
        assert!(e.balance().abs() < 1e-15, "t {t}: {e:?}");
    }
    let euler = history(&spring("ddtScheme 1", 30, dt));
    for (n, (t, _, e)) in euler.iter().enumerate() {
        let exact = e0 / (1.0 + omega * omega * dt * dt).powi(n as i32 + 1);
        assert!(
            (mechanical(e) / exact - 1.0).abs() < 1e-10,
            "t {t}: {} vs {exact}",
            mechanical(e)
        );
    }
    for scheme in ["ddtScheme 0", "ddtScheme 2 gamma 0.6 beta 0.3025"] {
        let h = history(&spring(scheme, 40, dt));
        let energies: Vec<f64> = h.iter().map(|(_, _, e)| mechanical(e)).collect();
        let last = *energies.last().unwrap();
        assert!(last < 0.9 * e0 && last > 0.0, "{scheme}: {energies:?}");
    }
}

/// Mass-proportional damping (`eta`): the energy balance holds with the damping's work counted
/// (to round-off, trapezoidal rule), and the mechanical energy decays as e^(−ηt) (a lightly
/// damped oscillator, ±2 % over two periods).
#[test]
fn mass_proportional_damping_dissipates_what_the_balance_counts() {
    let omega = 200f64.sqrt();
    let dt = 2.0 * std::f64::consts::PI / omega / 40.0;
    let eta = 0.5;
    let h = history(&spring(&format!("ddtScheme 2 eta {eta}"), 80, dt));
    let e0 = 0.5 * 100.0 * 1e-4;
    for (t, _, e) in &h {
        assert!(e.balance().abs() < 1e-15, "t {t}: {e:?}");
        assert!(e.damping > 0.0 || *t < dt * 1.5);
    }
    let (t, _, e) = h.last().unwrap();
    let ratio = mechanical(e) / e0 / (-eta * t).exp();
    assert!((ratio - 1.0).abs() < 0.02, "t {t}: {ratio}");
}

/// Stiffness-proportional damping (`delta`) on the mass on a spring is mass-proportional
/// damping of η = δ·ω² (δ·K = η·M there: K = 100, M = ½): every scheme, HHT included, gives the
/// same steps to round-off, its velocity's history taking the forces' rate as it takes v (OOFEM's
/// `DIIDynamic` puts Newmark's a6 there: a spurious δΔt(1−γ)·K·Δuₙ, its QUIRK). With the
/// trapezoidal rule the energy balance counts the damping's work to round-off.
#[test]
fn stiffness_proportional_damping_is_mass_proportional_on_a_single_mode() {
    let omega2: f64 = 200.0;
    let dt = 2.0 * std::f64::consts::PI / omega2.sqrt() / 20.0;
    let delta = 0.004;
    for scheme in [
        "ddtScheme 0",
        "ddtScheme 1",
        "ddtScheme 2",
        "ddtScheme 2 gamma 0.6 beta 0.3025",
        "ddtScheme 2 rhoinf 0.8",
    ] {
        for analysis in ["NonLinearDynamic", "DIIDynamic"] {
            let by_k = spring(&format!("{scheme} delta {delta}"), 40, dt)
                .replace("NonLinearDynamic", analysis);
            let by_m = spring(&format!("{scheme} eta {}", delta * omega2), 40, dt)
                .replace("NonLinearDynamic", analysis);
            let (a, b) = (history(&by_k), history(&by_m));
            for ((t, u, e), (_, v, f)) in a.iter().zip(&b) {
                assert!(
                    (u - v).abs() < 1e-15,
                    "{scheme} {analysis} t {t}: {u} vs {v}"
                );
                assert!(
                    (e.damping - f.damping).abs() < 1e-15,
                    "{scheme} {analysis} t {t}: {e:?} vs {f:?}"
                );
                // (The trapezoidal rule keeps the energy; the others dissipate some of it.)
                if scheme == "ddtScheme 2" {
                    assert!(e.balance().abs() < 1e-15, "{scheme} t {t}: {e:?}");
                }
            }
            let (_, _, last) = a.last().unwrap();
            assert!(
                last.damping > 0.01 * 0.5 * 100.0 * 1e-4,
                "{scheme}: {last:?}"
            );
        }
    }
}

/// Stiffness-proportional damping damps each mode of a bar by its own frequency, ζ = δω/2: a
/// fixed-free bar of 8 elements (lumped mass) started at rest in its first or its second mode
/// keeps the mode's shape (to 1e-12) and its modal energy ½(q̇² + ω²q²) follows the damped
/// oscillator's, within 0.2 % of the start's over two periods (trapezoidal rule, 200 steps a
/// period; the second mode, three times as fast, loses 9 times the first's energy a period).
/// The balance counts the damping's work to round-off.
#[test]
fn stiffness_proportional_damping_damps_a_bar_mode_by_its_frequency() {
    let n = 8;
    let (e, rho, delta) = (100.0, 1.0, 2e-3);
    let h = 1.0 / n as f64;
    let nodes: String = (0..=n)
        .map(|i| format!("node {} coords 1 {}\n", i + 1, h * i as f64))
        .collect();
    let elements: String = (0..n)
        .map(|i| {
            format!(
                "Truss1d {} nodes 2 {} {} crossSect 1 mat 1\n",
                i + 1,
                i + 1,
                i + 2
            )
        })
        .collect();
    for m in [1, 2] {
        // The discrete mode u_j = sin(κj), κ = (2m−1)π/(2n), ω² = (4E/(ρh²)) sin²(κ/2).
        let kappa = (2 * m - 1) as f64 * std::f64::consts::PI / (2.0 * n as f64);
        let omega = (4.0 * e / (rho * h * h)).sqrt() * (kappa / 2.0).sin();
        let dt = 2.0 * std::f64::consts::PI / omega / 200.0;
        let (ics, sets): (String, String) = (1..=n)
            .map(|j| {
                (
                    format!(
                        "InitialCondition {j} conditions 1 u {} set {} dofs 1 1\n",
                        0.001 * (kappa * j as f64).sin(),
                        j + 2
                    ),
                    format!("Set {} nodes 1 {}\n", j + 2, j + 1),
                )
            })
            .unzip();
        let text = format!(
            "bar.out\nbar\nNonLinearDynamic nsteps 400 deltat {dt} ddtScheme 2 delta {delta} \
             lumpedmass rtolf 1e-12 manrmsteps 1\ndomain 1dTruss\nOutputManager\n\
             ndofman {} nelem {n} ncrosssect 1 nmat 1 nbc 1 nic {n} nltf 1 nset {}\n\
             {nodes}{elements}SimpleCS 1 area 1 material 1 set 1\n\
             IsoLE 1 d {rho} E {e} n 0 tAlpha 0\n\
             BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n{ics}\
             ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 nodes 1 1\n{sets}",
            n + 1,
            n + 2
        );
        let model = crate::common::model_from_text(&text).unwrap();
        let zeta = delta * omega / 2.0;
        let wd = omega * (1.0 - zeta * zeta).sqrt();
        let modal = |q: f64, qd: f64| 0.5 * (qd * qd + omega * omega * q * q);
        let e0 = modal(0.001, 0.0);
        let mut steps = 0;
        run_analysis(&model, &crate::common::quiet(), |r| {
            let motion = r.motion.unwrap();
            let en = motion.energy;
            assert!(en.balance().abs() < 1e-16, "mode {m} t {}: {en:?}", r.time);
            // The free end's φ = sin(κn) = ±1.
            let phi = (kappa * n as f64).sin();
            let q = 0.001 * r.displacement(n, 1).unwrap() / (0.001 * phi);
            let qd = motion.velocity[r.dofs.code(n, 1).unwrap()] / phi;
            for j in 1..=n {
                let u = r.displacement(j, 1).unwrap();
                let expect = q * (kappa * j as f64).sin();
                assert!((u - expect).abs() < 1e-12 * 0.001, "mode {m} node {j}: {u}");
            }
            let t = r.time;
            let decay = (-zeta * omega * t).exp();
            let q_exact = 0.001 * decay * ((wd * t).cos() + zeta * omega / wd * (wd * t).sin());
            let qd_exact = -0.001 * omega * omega / wd * decay * (wd * t).sin();
            let (num, exact) = (modal(q, qd), modal(q_exact, qd_exact));
            assert!(
                (num - exact).abs() < 2e-3 * e0,
                "mode {m} t {t}: {num} vs {exact}"
            );
            steps += 1;
            Ok(())
        })
        .unwrap();
        assert_eq!(steps, 400);
    }
}

/// A column of `n` square plane stress elements (width 0.1, length 1, E = 1, ρ = 1, ν = 0: wave
/// speed 1) falling at V = 0.1 onto a rigid floor 0.01 below (`planecontactsegment`), its bottom
/// nodes in contact by `law`; u_x held; `extra` on the analysis record; steps of `dt` until it
/// has been off the floor for 0.5, or `nsteps`.
fn falling_rod(n: usize, dt: f64, law: &str, extra: &str, nsteps: Option<usize>) -> String {
    let (length, width, gap, speed) = (1.0, 0.1, 0.01, 0.1);
    let extra = if extra.is_empty() {
        String::new()
    } else {
        format!(" {extra}")
    };
    let nsteps = nsteps.unwrap_or(((gap / speed + 2.0 * length + 0.5) / dt).round() as usize);
    let mut nodes = Vec::new();
    for j in 0..=n {
        let y = gap + length * j as f64 / n as f64;
        for x in [0.0, width] {
            nodes.push(format!("node {} coords 2 {x} {y}", nodes.len() + 1));
        }
    }
    let elements: Vec<String> = (0..n)
        .map(|j| {
            let (a, b) = (2 * j + 1, 2 * j + 2);
            format!(
                "PlaneStress2d {} nodes 4 {a} {b} {} {} crossSect 1 mat 1",
                j + 1,
                b + 2,
                a + 2
            )
        })
        .collect();
    let all: Vec<String> = (1..=nodes.len()).map(|k| k.to_string()).collect();
    format!(
        "rod_impact.out\nElastic rod dropped on a rigid floor (implicit dynamics)\n\
         NonLinearDynamic nsteps {nsteps} deltat {dt} ddtScheme 2 rtolf 1e-10 manrmsteps 1 \
         maxiter 30{extra}\ndomain 2dPlaneStress\nOutputManager tstep_all\n\
         ndofman {} nelem {n} ncrosssect 1 nmat 1 nbc 2 nic 1 nltf 1 nset 3 ncontactseg 1\n{}\n{}\n\
         planecontactsegment 1 point 2 0 0 normal 2 0 1\nSimpleCS 1 thick 1 material 1 set 1\n\
         IsoLE 1 d 1 E 1 n 0 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n\
         {law} slaveset 3 segmentset 1 1\n\
         InitialCondition 1 conditions 1 v {} set 2 dofs 1 2\nConstantFunction 1 f(t) 1\n\
         Set 1 allelements\nSet 2 nodes {} {}\nSet 3 nodes 2 1 2\n",
        nodes.len(),
        nodes.join("\n"),
        elements.join("\n"),
        -speed,
        all.len(),
        all.join(" ")
    )
}

/// What the falling rod did: the times of its first and last step in contact, the contact
/// force per step, the rod's mean velocity after it left the floor, the last step's energies
/// and the most Newton iterations of a step.
struct Impact {
    first: f64,
    last: f64,
    forces: Vec<f64>,
    rebound: f64,
    energy: Energy,
    iterations: usize,
}

fn impact(n: usize, dt: f64, law: &str, extra: &str) -> Impact {
    let mut text = falling_rod(n, dt, law, extra, None);
    if (n, extra) == (40, "") && law.contains("multiplier") {
        // examples/rod_impact.in is this model with its comments.
        let example = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/rod_impact.in"),
        )
        .unwrap();
        let records: Vec<&str> = example.lines().filter(|l| !l.starts_with('#')).collect();
        assert_eq!(
            records.join("\n") + "\n",
            text,
            "examples/rod_impact.in is out of date"
        );
        text = example;
    }
    run_impact(n, &text)
}

/// [`impact`] of the rod of `n` elements in the input `text`.
fn run_impact(n: usize, text: &str) -> Impact {
    let model = crate::common::model_from_text(text).unwrap();
    let mut out = Impact {
        first: f64::NAN,
        last: f64::NAN,
        forces: Vec::new(),
        rebound: 0.0,
        energy: Energy::default(),
        iterations: 0,
    };
    run_analysis(&model, &crate::common::quiet(), |r| {
        let force: f64 = r.contact.iter().map(|c| c.force).sum();
        out.forces.push(force);
        // In contact: a force above round-off (a thousandth of the plateau ρcV·A = 0.01).
        if force > 1e-5 {
            out.last = r.time;
            if out.first.is_nan() {
                out.first = r.time;
            }
        }
        let m = r.motion.unwrap();
        // The momentum per unit mass: each element's mean velocity (linear elements, consistent
        // mass), the bottom element's taken from its upper nodes (its mass moved there).
        let v = |row: usize| m.velocity[r.dofs.code(2 * row, 2).unwrap()];
        out.rebound = (0..n)
            .map(|j| {
                if j == 0 {
                    v(1)
                } else {
                    0.5 * (v(j) + v(j + 1))
                }
            })
            .sum::<f64>()
            / n as f64;
        out.energy = m.energy;
        out.iterations = out.iterations.max(r.info.iterations);
        Ok(())
    })
    .unwrap();
    out
}

/// An elastic rod dropped on a rigid floor at V (1D wave theory: contact from t = g/V for 2L/c,
/// a contact stress ρcV, the rod leaving at −V with its energy): with the contact nodes' mass
/// moved into the rod (the default) the trapezoidal rule gives, with multipliers and with a
/// penalty, the contact time within 2 % (1.25 % at 80 elements), the force's plateau within
/// 0.1 %, the rebound speed within 2 % and the energy within 0.2 %, in at most 6 iterations a
/// step. Measured (both laws): contact 2.025 and 2.0125, rebound −1.6 % and −1.2 %, energy
/// +0.08 % and +0.04 % at 40 and 80 elements. With OOFEM's mass on the contact nodes (`keepcontactmass`) the force chatters between 0
/// and 3.5 times its value and the rod leaves with about 7 times its energy.
#[test]
fn a_rod_dropped_on_a_rigid_floor_rebounds_as_wave_theory() {
    let (speed, width) = (0.1, 0.1);
    let kinetic = 0.5 * width * speed * speed;
    for law in [
        "n2slagrangianmultipliercontact 2 loadTimeFunction 1",
        "n2spenaltycontact 2 loadTimeFunction 1",
    ] {
        for (n, dt, tolerance) in [(40, 0.025, 0.02), (80, 0.0125, 0.0125)] {
            let r = impact(n, dt, law, "");
            let duration = r.last - r.first + dt;
            assert!(
                (duration / 2.0 - 1.0).abs() <= tolerance + 1e-9,
                "{law} {n}: contact from {} to {}",
                r.first,
                r.last
            );
            let plateau = r.forces[r.forces.len() / 2];
            assert!(
                (plateau / (speed * width) - 1.0).abs() < 1e-3,
                "{law}: {plateau}"
            );
            assert!(
                (r.rebound / speed - 1.0).abs() < 0.02,
                "{law}: rebound {}",
                r.rebound
            );
            let kept = r.energy.kinetic + r.energy.internal;
            assert!((kept / kinetic - 1.0).abs() < 2e-3, "{law}: {:?}", r.energy);
            assert!(r.energy.balance().abs() < 1e-12, "{:?}", r.energy);
            assert!(r.iterations <= 6, "{law}: {} iterations", r.iterations);
        }
    }
    let chatter = impact(
        40,
        0.025,
        "n2slagrangianmultipliercontact 2 loadTimeFunction 1",
        "keepcontactmass",
    );
    let kept = chatter.energy.kinetic + chatter.energy.internal;
    assert!(kept > 3.0 * kinetic, "{:?}", chatter.energy);
}

/// A free body started at a uniform velocity translates at it exactly, with consistent and with
/// lumped mass (each holds a translation's momentum): u = V t at every node.
#[test]
fn a_free_body_translates_at_its_initial_velocity() {
    for extra in ["", "lumpedmass"] {
        // The velocity along x, the bottom held in y (the rod never reaches the floor).
        let text = falling_rod(
            4,
            0.01,
            "n2spenaltycontact 2 loadTimeFunction 1",
            extra,
            Some(5),
        )
        .replace("dofs 1 2\n", "dofs 1 1\n")
        .replace("values 1 0 set 2", "values 1 0 set 3")
        .replace("dofs 1 1 values", "dofs 1 2 values");
        let model = crate::common::model_from_text(&text).unwrap();
        run_analysis(&model, &crate::common::quiet(), |r| {
            for n in 0..model.nodes.len() {
                let ux = r.displacement(n, 1).unwrap();
                assert!((ux + 0.1 * r.time).abs() < 1e-13, "{extra}: node {n}: {ux}");
            }
            Ok(())
        })
        .unwrap();
    }
}

/// `NlDEIDynamic`'s central differences give u_n = u₀ cos(ω̃ t_n) with cos(ω̃h) = 1 − ω²h²/2
/// exactly (hertz starts at v_½ = v₀ + (h/2) a₀); a `deltat` of 0.2 above the stable step
/// 2/ω = 0.1414 (the bound is exact for a bar) is taken in two substeps of 0.1, with a warning,
/// and lands on the same discrete solution at h = 0.1 (OOFEM's diagonal estimate would have
/// allowed √2 times the stable step here).
#[test]
fn central_differences_follow_their_discrete_solution_within_the_stable_step() {
    let omega = 200f64.sqrt();
    for (dt, h, substeps) in [(0.02, 0.02, 1), (0.2, 0.1, 2)] {
        let text = spring("", 10, dt).replace(
            &format!("NonLinearDynamic nsteps 10 deltat {dt}  rtolf 1e-12 manrmsteps 1"),
            &format!("NlDEIDynamic nsteps 10 deltat {dt} dumpcoef 0"),
        );
        let model = crate::common::model_from_text(&text).unwrap();
        let discrete = (1.0 - omega * omega * h * h / 2.0).acos() / h;
        run_analysis(&model, &crate::common::quiet(), |r| {
            let u = r.displacement(1, 1).unwrap();
            let exact = 0.01 * (discrete * r.time).cos();
            assert!(
                (u - exact).abs() < 1e-13,
                "dt {dt}, t {}: {u} vs {exact}",
                r.time
            );
            assert_eq!(r.info.substeps, substeps);
            if r.step == 1 && substeps > 1 {
                assert!(
                    r.info
                        .warnings
                        .iter()
                        .any(|w| w.contains("above the stable time step")),
                    "{:?}",
                    r.info.warnings
                );
            }
            Ok(())
        })
        .unwrap();
    }
}

/// The dropped rod in explicit dynamics (penalty contact, the contact nodes' penalty their own
/// stiffness): contact time within 2 % (measured 2.025 and 2.0 at 40 and 80 elements), the mean
/// contact force over the middle of the contact within 2 % of ρcV·A (the bottom nodes ring on
/// the penalty), the rebound speed within 2 % and the energy within 1 %.
#[test]
fn a_rod_dropped_on_a_rigid_floor_rebounds_as_wave_theory_in_explicit_dynamics() {
    let (speed, width) = (0.1, 0.1);
    let kinetic = 0.5 * width * speed * speed;
    let law = "n2spenaltycontact 2 loadTimeFunction 1";
    for (n, dt) in [(40, 0.025), (80, 0.0125)] {
        let text = falling_rod(n, dt, law, "", None);
        let line = text.lines().nth(2).unwrap().to_string();
        let nsteps = line.split_whitespace().nth(2).unwrap();
        let explicit = format!("NlDEIDynamic nsteps {nsteps} deltat {dt} dumpcoef 0");
        let r = run_impact(n, &text.replace(&line, &explicit));
        let duration = r.last - r.first + dt;
        assert!(
            (duration / 2.0 - 1.0).abs() < 0.02,
            "{n}: contact from {} to {}",
            r.first,
            r.last
        );
        let middle = &r.forces[r.forces.len() / 4..r.forces.len() / 2];
        let mean = middle.iter().sum::<f64>() / middle.len() as f64;
        assert!((mean / (speed * width) - 1.0).abs() < 0.02, "{n}: {mean}");
        assert!(
            (r.rebound / speed - 1.0).abs() < 0.02,
            "{n}: rebound {}",
            r.rebound
        );
        let kept = r.energy.kinetic + r.energy.internal;
        assert!((kept / kinetic - 1.0).abs() < 0.01, "{n}: {:?}", r.energy);
    }
}

/// OOFEM's default three-point scheme (`ddtScheme 0`, its first step backward Euler: the mass
/// term of the tangent changes after it) and backward Euler on the dropped rod: each step
/// converges at once with the contact condensed (a stale factor of the first step's tangent
/// once left the second step's residual unchanged in every iteration), and the schemes lose
/// energy as they should, the balance counting what they lost (measured: 7.6 % and 27 %).
#[test]
fn dissipative_schemes_drop_the_rod_and_lose_energy() {
    let kinetic = 0.5 * 0.1 * 0.1 * 0.1;
    for (scheme, least, most) in [("ddtScheme 0", 0.03, 0.15), ("ddtScheme 1", 0.15, 0.4)] {
        let text = falling_rod(
            40,
            0.025,
            "n2slagrangianmultipliercontact 2 loadTimeFunction 1",
            "",
            None,
        )
        .replace(
            "ddtScheme 2 rtolf 1e-10 manrmsteps 1",
            &format!("{scheme} rtolf 1e-10"),
        );
        let r = run_impact(40, &text);
        let kept = r.energy.kinetic + r.energy.internal + r.energy.contact;
        let lost = 1.0 - kept / kinetic;
        assert!(lost > least && lost < most, "{scheme}: lost {lost}");
        assert!(
            (r.energy.balance() / kinetic + lost).abs() < 1e-9,
            "{scheme}: {:?}",
            r.energy
        );
        assert!(r.iterations <= 3, "{scheme}: {} iterations", r.iterations);
    }
}

/// Two equal columns of `n` square plane stress elements (width 0.1, length 1, E = 1, ρ = 1,
/// ν = 0: wave speed 1), 0.01 apart, the lower moving up at V = 0.1 and the upper down at V;
/// u_x held; the upper's bottom nodes meet the lower's top edge by `law` (node-to-segment or, for
/// an `s2s` law, mortar); steps of `dt` until they have been apart for 0.5.
fn colliding_rods(n: usize, dt: f64, law: &str) -> String {
    let (length, width, gap, speed) = (1.0, 0.1, 0.01, 0.1);
    let nsteps = ((gap / (2.0 * speed) + 2.0 * length + 0.5) / dt).round() as usize;
    let mut nodes = Vec::new();
    let mut elements = Vec::new();
    for y0 in [0.0, length + gap] {
        let base = nodes.len();
        for j in 0..=n {
            let y = y0 + length * j as f64 / n as f64;
            for x in [0.0, width] {
                nodes.push(format!("node {} coords 2 {x} {y}", nodes.len() + 1));
            }
        }
        for j in 0..n {
            let a = base + 2 * j + 1;
            elements.push(format!(
                "PlaneStress2d {} nodes 4 {a} {} {} {} crossSect 1 mat 1",
                elements.len() + 1,
                a + 1,
                a + 3,
                a + 2
            ));
        }
    }
    let list = |r: std::ops::RangeInclusive<usize>| {
        let v: Vec<String> = r.map(|k| k.to_string()).collect();
        format!("{} {}", v.len(), v.join(" "))
    };
    let half = 2 * (n + 1);
    let condition = if law.starts_with("s2s") {
        format!("{law} slavesegment 2 segmentset 1 1")
    } else {
        format!("{law} slaveset 5 segmentset 1 1")
    };
    format!(
        "rods.out\nTwo elastic rods collide (implicit dynamics)\n\
         NonLinearDynamic nsteps {nsteps} deltat {dt} ddtScheme 2 rtolf 1e-10 manrmsteps 1 \
         maxiter 30\ndomain 2dPlaneStress\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 2 nic 2 nltf 1 nset 7 ncontactseg 2\n\
         {}\n{}\nlinear2delementedgecontactsegment 1 edgeset 6\n\
         linear2delementedgecontactsegment 2 edgeset 7\nSimpleCS 1 thick 1 material 1 set 1\n\
         IsoLE 1 d 1 E 1 n 0 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n{condition}\n\
         InitialCondition 1 conditions 1 v {speed} set 3 dofs 1 2\n\
         InitialCondition 2 conditions 1 v {} set 4 dofs 1 2\nConstantFunction 1 f(t) 1\n\
         Set 1 allelements\nSet 2 nodes {}\nSet 3 nodes {}\nSet 4 nodes {}\n\
         Set 5 nodes 2 {} {}\nSet 6 elementboundaries 2 {n} 3\n\
         Set 7 elementboundaries 2 {} 1\n",
        nodes.len(),
        elements.len(),
        nodes.join("\n"),
        elements.join("\n"),
        -speed,
        list(1..=nodes.len()),
        list(1..=half),
        list(half + 1..=nodes.len()),
        half + 1,
        half + 2,
        n + 1,
    )
}

/// An elastic ring (radii 0.6 and 1, 48 × 3 plane strain quadrilaterals) 0.01 above an elastic
/// plate (4 × 0.5, 32 × 4, its base held), both E = 1, ν = 0.3, ρ = 1, the ring moving at 0.05
/// towards it at 45°; the ring's lower outer surface meets the plate's top by `law` (its nodes
/// for node-to-segment, its edges for an `s2s` law) with `friction`; 300 steps of 0.05; with
/// `nlgeo`, total Lagrangian elements.
fn ring_on_a_plate(law: &str, friction: f64, nlgeo: bool) -> String {
    let (nt, nr, inner, outer, gap, speed) = (48, 3, 0.6, 1.0, 0.01, 0.05);
    let (nx, ny, width, depth) = (32, 4, 4.0, 0.5);
    let mut nodes: Vec<[f64; 2]> = Vec::new();
    let mut elements: Vec<[usize; 4]> = Vec::new();
    let plate = |i: usize, j: usize| j * (nx + 1) + i + 1;
    for j in 0..=ny {
        for i in 0..=nx {
            let (x, y) = (i as f64 / nx as f64, j as f64 / ny as f64);
            nodes.push([width * (x - 0.5), depth * (y - 1.0)]);
        }
    }
    // The quadrilateral of a grid `id` from (a, b) to (a + 1, b + 1), counterclockwise.
    let quad = |id: &dyn Fn(usize, usize) -> usize, a: usize, b: usize| {
        [id(a, b), id(a + 1, b), id(a + 1, b + 1), id(a, b + 1)]
    };
    for j in 0..ny {
        for i in 0..nx {
            elements.push(quad(&plate, i, j));
        }
    }
    let (first, plate_elements) = (nodes.len() + 1, elements.len());
    let ring = |k: usize, j: usize| first + k * nt + j % nt;
    let angle = |j: f64| 2.0 * std::f64::consts::PI * j / nt as f64;
    for k in 0..=nr {
        let r = inner + (outer - inner) * k as f64 / nr as f64;
        for j in 0..nt {
            let t = angle(j as f64);
            nodes.push([r * t.cos(), outer + gap + r * t.sin()]);
        }
    }
    for k in 0..nr {
        for j in 0..nt {
            elements.push(quad(&ring, k, j));
        }
    }
    let list = |v: Vec<usize>| {
        let s: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        format!("{} {}", s.len(), s.join(" "))
    };
    // The lower part of the ring's outer surface: its nodes, and its elements' edge 2.
    let lower = |t: f64| angle(t).sin() < -0.3;
    let slaves: Vec<usize> = (0..nt)
        .filter(|&j| lower(j as f64))
        .map(|j| ring(nr, j))
        .collect();
    let edges: Vec<String> = (0..nt)
        .filter(|&j| lower(j as f64 + 0.5))
        .map(|j| format!("{} 2", plate_elements + (nr - 1) * nt + j + 1))
        .collect();
    let top: Vec<String> = (0..nx)
        .map(|i| format!("{} 3", (ny - 1) * nx + i + 1))
        .collect();
    let condition = if law.starts_with("s2s") {
        format!("{law} slavesegment 2 segmentset 1 1")
    } else {
        format!("{law} slaveset 3 segmentset 1 1")
    };
    let friction = if friction > 0.0 {
        format!(" friction {friction}")
    } else {
        String::new()
    };
    let v = speed * std::f64::consts::FRAC_1_SQRT_2;
    format!(
        "ring.out\nA ring hits a plate at an angle\n\
         NonLinearDynamic nsteps 300 deltat 0.05 ddtScheme 2 rtolf 1e-9 manrmsteps 1 maxiter 40\n\
         domain PlaneStrain\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 2 nic 2 nltf 1 nset 6 ncontactseg 2\n{}\n{}\n\
         linear2delementedgecontactsegment 1 edgeset 5\n\
         linear2delementedgecontactsegment 2 edgeset 6\nSimpleCS 1 thick 1 material 1 set 1\n\
         IsoLE 1 d 1 E 1 n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 2\n\
         {condition}{friction}\n\
         InitialCondition 1 conditions 1 v {v} set 4 dofs 1 1\n\
         InitialCondition 2 conditions 1 v {} set 4 dofs 1 2\nConstantFunction 1 f(t) 1\n\
         Set 1 allelements\nSet 2 nodes {}\nSet 3 nodes {}\nSet 4 nodes {}\n\
         Set 5 elementboundaries {} {}\nSet 6 elementboundaries {} {}\n",
        nodes.len(),
        elements.len(),
        nodes
            .iter()
            .enumerate()
            .map(|(k, x)| format!("node {} coords 2 {} {}", k + 1, x[0], x[1]))
            .collect::<Vec<_>>()
            .join("\n"),
        elements
            .iter()
            .enumerate()
            .map(|(k, n)| format!(
                "Quad1PlaneStrain {} nodes 4 {} {} {} {} crossSect 1 mat 1 nlgeo {}",
                k + 1,
                n[0],
                n[1],
                n[2],
                n[3],
                u8::from(nlgeo)
            ))
            .collect::<Vec<_>>()
            .join("\n"),
        -v,
        list((0..=nx).map(|i| plate(i, 0)).collect()),
        list(slaves),
        list((first..=nodes.len()).collect()),
        2 * top.len(),
        top.join(" "),
        2 * edges.len(),
        edges.join(" "),
    )
}

/// An elastic ring hitting an elastic plate at 45°, node-to-segment and mortar, multipliers and
/// penalty: with Coulomb friction (μ = 0.3) its energy never rises and what it loses is the
/// contact's work, which friction does (to 1e-9 of the energy; a fifth of it here: measured
/// 0.200 node-to-segment, 0.191 mortar); without friction it leaves with its energy within
/// 1 % (measured: 0.26 % lost node-to-segment, whose energy rose 0.14 % on the way; mortar
/// 0.013 %), in at most 4 iterations a step; with friction in large deformation too
/// (node-to-segment multipliers and mortar penalty).
#[test]
fn a_ring_hitting_a_plate_at_an_angle_loses_to_friction_what_friction_works() {
    let mech = |e: &Energy| e.kinetic + e.internal;
    for law in [
        "n2slagrangianmultipliercontact 2 loadTimeFunction 1",
        "n2spenaltycontact 2 loadTimeFunction 1",
        "s2slagrangianmultipliercontact 2 loadTimeFunction 1",
        "s2spenaltycontact 2 loadTimeFunction 1",
    ] {
        // Large deformation with friction for one law of each formulation.
        let large = law.contains("multiplier") == law.starts_with("n2s");
        for (mu, nlgeo) in [(0.3, false), (0.0, false), (0.3, true)] {
            if nlgeo && !large {
                continue;
            }
            let text = ring_on_a_plate(law, mu, nlgeo);
            let model = crate::common::model_from_text(&text).unwrap();
            let (mut initial, mut highest, mut last_contact) = (f64::NAN, 0.0f64, 0);
            let (mut energy, mut iterations) = (Energy::default(), 0);
            run_analysis(&model, &crate::common::quiet(), |r| {
                let m = r.motion.unwrap();
                if initial.is_nan() {
                    initial = mech(&m.energy);
                }
                highest = highest.max(mech(&m.energy));
                if r.contact.iter().any(|c| c.force.abs() > 1e-9) {
                    last_contact = r.step;
                }
                energy = m.energy;
                iterations = iterations.max(r.info.iterations);
                Ok(())
            })
            .unwrap();
            let case = format!("{law} μ {mu} nlgeo {nlgeo}: {energy:?}");
            assert!(
                last_contact > 5 && last_contact < 280,
                "{case}: {last_contact}"
            );
            let lost = 1.0 - mech(&energy) / initial;
            assert!(energy.balance().abs() < 1e-9 * initial, "{case}");
            if mu > 0.0 {
                assert!(
                    highest <= initial * (1.0 + 1e-9),
                    "{case}: rose to {highest}"
                );
                assert!((lost - energy.contact / initial).abs() < 1e-9, "{case}");
                assert!(lost > 0.1, "{case}: lost {lost}");
            } else {
                assert!(highest <= initial * 1.005, "{case}: rose to {highest}");
                assert!(lost.abs() < 0.01, "{case}: lost {lost}");
            }
            assert!(iterations <= 4, "{case}: {iterations} iterations");
        }
    }
}

/// Two equal elastic rods colliding at ±V (1D wave theory: each meets the other as a rigid wall
/// at the plane of symmetry, contact lasts 2L/c under ρcV and each rod leaves at ∓V with its
/// energy), with node-to-segment and mortar contact, multipliers and penalty: the contact time
/// within 2 %, the force's plateau within 0.1 %, the rods' mean velocities ∓V within 2 % after
/// they part, the energy within 0.2 %, and the momentum zero at every step (action equals
/// reaction: one rod is slave, the other master). Both sides' contact nodes are without mass:
/// with the master edge's mass kept the plateau swung ±8 % every third step.
#[test]
fn two_rods_collide_as_wave_theory() {
    let (n, dt, speed, width) = (40, 0.025, 0.1, 0.1);
    let kinetic = 2.0 * 0.5 * width * speed * speed;
    for law in [
        "n2slagrangianmultipliercontact 2 loadTimeFunction 1",
        "n2spenaltycontact 2 loadTimeFunction 1",
        "s2slagrangianmultipliercontact 2 loadTimeFunction 1",
        "s2spenaltycontact 2 loadTimeFunction 1",
    ] {
        let model = crate::common::model_from_text(&colliding_rods(n, dt, law)).unwrap();
        let (mut first, mut last) = (f64::NAN, f64::NAN);
        let (mut forces, mut speeds, mut energy) = (Vec::new(), (0.0, 0.0), Energy::default());
        let mut iterations = 0;
        run_analysis(&model, &crate::common::quiet(), |r| {
            let force: f64 = r.contact.iter().map(|c| c.force).sum();
            forces.push(force);
            if force.abs() > 1e-5 {
                last = r.time;
                if first.is_nan() {
                    first = r.time;
                }
            }
            // Each element's momentum per unit mass is its nodes' mean velocity (consistent
            // mass of a bilinear square), the contact elements' that of their other two nodes
            // (their contact nodes' mass moved there).
            let m = r.motion.unwrap();
            let v = |row: usize| {
                let at = |node: usize| m.velocity[r.dofs.code(node, 2).unwrap()];
                0.5 * (at(2 * row) + at(2 * row + 1))
            };
            let rod = |rows: std::ops::Range<usize>, contact: usize, other: usize| {
                let mut sum = 0.0;
                for j in rows {
                    sum += if j == contact {
                        v(other)
                    } else {
                        0.5 * (v(j) + v(j + 1))
                    };
                }
                sum / n as f64
            };
            let o = n + 1;
            speeds = (rod(0..n, n - 1, n - 1), rod(o..o + n, o, o + 1));
            assert!(
                (speeds.0 + speeds.1).abs() < 1e-12,
                "{law} t {}: momentum {speeds:?}",
                r.time
            );
            energy = m.energy;
            iterations = iterations.max(r.info.iterations);
            Ok(())
        })
        .unwrap();
        let duration = last - first + dt;
        assert!(
            (duration / 2.0 - 1.0).abs() <= 0.02 + 1e-9,
            "{law}: contact from {first} to {last}"
        );
        let plateau = forces[forces.len() / 2];
        assert!(
            (plateau / (speed * width) - 1.0).abs() < 1e-3,
            "{law}: {plateau}"
        );
        assert!(
            (speeds.0 / speed + 1.0).abs() < 0.02 && (speeds.1 / speed - 1.0).abs() < 0.02,
            "{law}: rebound {speeds:?}"
        );
        let kept = energy.kinetic + energy.internal;
        assert!((kept / kinetic - 1.0).abs() < 2e-3, "{law}: {energy:?}");
        assert!(energy.balance().abs() < 1e-12, "{law}: {energy:?}");
        assert!(iterations <= 6, "{law}: {iterations} iterations");
    }
}

/// An elastic ball (radius 1, E = 1, ν = 0.3, ρ = 1) dropped at `speed` on a rigid floor 0.002
/// below it, axisymmetric: its meridian half-disk in `nt` sectors, graded towards the bottom
/// pole (θ = −90° + 180° s^1.6), and `nr` rings graded by 1/`q` towards the surface, a fan of
/// triangles at the centre; the surface below 30° from the pole in contact by multipliers;
/// Newmark's trapezoidal rule at `dt` until 1.3 Hertz impact times after the touch.
fn dropped_ball(nt: usize, nr: usize, dt: f64, speed: f64, q: f64) -> (String, f64) {
    use std::f64::consts::PI;
    let (radius, gap) = (1.0, 0.002);
    let centre = radius + gap;
    let weights: Vec<f64> = (0..nr).map(|k| q.powi((nr - 1 - k) as i32)).collect();
    let total: f64 = weights.iter().sum();
    let rings: Vec<f64> = (0..nr)
        .map(|i| radius * weights[..=i].iter().sum::<f64>() / total)
        .collect();
    let theta = |j: usize| -PI / 2.0 + PI * (j as f64 / nt as f64).powf(1.6);
    let mut nodes = vec![format!("node 1 coords 2 0 {centre}")];
    let id = |i: usize, j: usize| 2 + i * (nt + 1) + j;
    let (mut axis, mut slaves) = (vec![1], Vec::new());
    for (i, &r) in rings.iter().enumerate() {
        for j in 0..=nt {
            let x = if j == 0 || j == nt {
                0.0
            } else {
                r * theta(j).cos()
            };
            let y = centre + r * theta(j).sin();
            nodes.push(format!("node {} coords 2 {x:.15} {y:.15}", id(i, j)));
            if j == 0 || j == nt {
                axis.push(id(i, j));
            }
            if i == nr - 1 && theta(j) < -PI / 3.0 {
                slaves.push(id(i, j));
            }
        }
    }
    let mut elements = Vec::new();
    for j in 0..nt {
        let n = [1, id(0, j), id(0, j + 1)];
        elements.push(format!(
            "Axisymm3d {} nodes 3 {} {} {}",
            elements.len() + 1,
            n[0],
            n[1],
            n[2]
        ));
    }
    for i in 0..nr - 1 {
        for j in 0..nt {
            let n = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            elements.push(format!(
                "L4Axisymm {} nodes 4 {} {} {} {}",
                elements.len() + 1,
                n[0],
                n[1],
                n[2],
                n[3]
            ));
        }
    }
    let tc = hertz_impact(speed).0;
    let nsteps = ((gap / speed + 1.3 * tc) / dt).round() as usize;
    let list = |v: &[usize]| {
        let s: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        format!("{} {}", v.len(), s.join(" "))
    };
    let all: Vec<usize> = (1..=nodes.len()).collect();
    let text = format!(
        "ball.out\nelastic ball on a rigid floor\nNonLinearDynamic nsteps {nsteps} deltat {dt} \
         ddtScheme 2 rtolf 1e-8 manrmsteps 1 maxiter 30\ndomain 2dPlaneStress\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 2 nic 1 nltf 1 nset 4 ncontactseg 1\n{}\n{}\n\
         planecontactsegment 1 point 2 0 0 normal 2 0 1\nSimpleCS 1 material 1 set 1\n\
         IsoLE 1 d 1 E 1 n 0.3 tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 1 values 1 0 set 2\n\
         n2slagrangianmultipliercontact 2 loadTimeFunction 1 slaveset 3 segmentset 1 1\n\
         InitialCondition 1 conditions 1 v {} set 4 dofs 1 2\nConstantFunction 1 f(t) 1\n\
         Set 1 allelements\nSet 2 nodes {}\nSet 3 nodes {}\nSet 4 nodes {}\n",
        nodes.len(),
        elements.len(),
        nodes.join("\n"),
        elements.join("\n"),
        -speed,
        list(&axis),
        list(&slaves),
        list(&all)
    );
    (text, gap / speed)
}

/// Hertz's impact of the ball on a rigid floor at `speed` (Johnson, Contact Mechanics §11.4):
/// the contact time 2.87 (m²/(R E*² V))^(1/5) and the largest force (4/3) E* √R δ^(3/2) at the
/// approach δ = (15 m V²/(16 E* √R))^(2/5), m the whole ball's mass, E* = E/(1 − ν²).
fn hertz_impact(speed: f64) -> (f64, f64) {
    let mass = 4.0 / 3.0 * std::f64::consts::PI;
    let modulus = 1.0 / (1.0 - 0.09);
    let tc = 2.87 * (mass * mass / (modulus * modulus * speed)).powf(0.2);
    let approach = (15.0 * mass * speed * speed / (16.0 * modulus)).powf(0.4);
    (tc, 4.0 / 3.0 * modulus * approach.powf(1.5))
}

/// The dropped ball's contact time and largest force (whole ball: 2π times the force per
/// radian), and its energy at the end over the start.
fn ball_impact(nt: usize, nr: usize, dt: f64, speed: f64, q: f64) -> (f64, f64, f64) {
    let (text, touch) = dropped_ball(nt, nr, dt, speed, q);
    let model = crate::common::model_from_text(&text).unwrap();
    let (mut last, mut peak, mut energy) = (0.0, 0.0f64, 0.0);
    run_analysis(&model, &crate::common::quiet(), |r| {
        let force: f64 =
            r.contact.iter().map(|c| c.force).sum::<f64>() * 2.0 * std::f64::consts::PI;
        if force > 1e-12 {
            last = r.time;
        }
        peak = peak.max(force);
        let e = r.motion.unwrap().energy;
        energy = (e.kinetic + e.internal + e.contact) / e.initial;
        Ok(())
    })
    .unwrap();
    (last + 0.5 * dt - touch, peak, energy)
}

/// Hertz's impact of an elastic ball on a rigid floor, axisymmetric, implicit with the contact
/// nodes' mass moved into the ball: at V = 0.002 (contact radius 0.11 R) the contact lasts
/// 2.9 % less than Hertz's 16.99 and the largest force is 4.7 % above his (the same on a mesh
/// twice as fine: the difference is Hertz's, a small-contact and quasi-static theory, and
/// shrinks with the contact), the ball leaves with its energy (kinetic, strain and the
/// contact's work) to 1e-10. The long test at V = 0.0005 (contact radius 0.06 R): −2.3 % and
/// +2.9 %.
#[test]
fn an_elastic_ball_bounces_on_a_floor_as_hertz_impact() {
    let (tc, force) = hertz_impact(0.002);
    let (duration, peak, energy) = ball_impact(80, 24, 0.2, 0.002, 1.2);
    assert!(
        (duration / tc - 1.0).abs() < 0.05,
        "contact {duration} vs {tc}"
    );
    assert!((peak / force - 1.0).abs() < 0.06, "force {peak} vs {force}");
    assert!((energy - 1.0).abs() < 1e-3, "energy {energy}");
}

#[test]
#[ignore = "long: the ball impact at a smaller speed on a finer mesh (7 s)"]
fn a_slower_ball_on_a_finer_mesh_comes_closer_to_hertz_impact() {
    let (tc, force) = hertz_impact(0.0005);
    let (duration, peak, energy) = ball_impact(140, 30, 0.2, 0.0005, 1.15);
    assert!(
        (duration / tc - 1.0).abs() < 0.035,
        "contact {duration} vs {tc}"
    );
    assert!(
        (peak / force - 1.0).abs() < 0.035,
        "force {peak} vs {force}"
    );
    assert!((energy - 1.0).abs() < 1e-3, "energy {energy}");
}

/// A short step on a slow oscillation: the inertia M·c₀u and its history nearly cancel, and
/// the residual is measured against them (as OOFEM's against its load with the inertia
/// history), so Newton stops at round-off in one iteration (it stalled above rtolf 1e-12 when
/// the reference was the forces at the solution alone).
#[test]
fn a_short_step_converges_at_round_off_of_the_inertia() {
    let omega = 200f64.sqrt();
    let dt = 2.0 * std::f64::consts::PI / omega / 2000.0;
    let model = crate::common::model_from_text(&spring("ddtScheme 2", 5, dt)).unwrap();
    run_analysis(&model, &crate::common::quiet(), |r| {
        assert!(r.info.iterations <= 2, "{:?}", r.info.residual_history);
        Ok(())
    })
    .unwrap();
}

/// A block (1 × 0.25, ρ = 1, E = 1000) under gravity 10 on a rigid floor with Coulomb friction
/// μ = 0.3 (multipliers), started sliding at 1: it stops after V/(μg) = 1/3 having slid
/// V²/(2μg) = 1/6 (within 2 %: the block rings elastically as it brakes), and the friction's
/// work (the contact's) takes the kinetic energy, the balance closing to 1e-10.
#[test]
fn a_block_sliding_on_a_floor_stops_where_coulomb_friction_says() {
    let (nx, ny) = (8, 2);
    let id = |i: usize, j: usize| j * (nx + 1) + i + 1;
    let mut nodes = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            nodes.push(format!(
                "node {} coords 2 {} {}",
                id(i, j),
                i as f64 / nx as f64,
                0.25 * j as f64 / ny as f64
            ));
        }
    }
    let mut elements = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let n = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            elements.push(format!(
                "PlaneStress2d {} nodes 4 {} {} {} {} crossSect 1 mat 1",
                elements.len() + 1,
                n[0],
                n[1],
                n[2],
                n[3]
            ));
        }
    }
    let bottom: Vec<String> = (0..=nx).map(|i| id(i, 0).to_string()).collect();
    let all: Vec<String> = (1..=nodes.len()).map(|k| k.to_string()).collect();
    let text = format!(
        "slide.out\nsliding block\nNonLinearDynamic nsteps 50 deltat 0.01 ddtScheme 2 rtolf 1e-9 \
         manrmsteps 1 maxiter 60\ndomain 2dPlaneStress\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 2 nic 1 nltf 1 nset 3 ncontactseg 1\n{}\n{}\n\
         planecontactsegment 1 point 2 0 0 normal 2 0 1\nSimpleCS 1 thick 1 material 1 set 1\n\
         IsoLE 1 d 1 E 1000 n 0.3 tAlpha 0\nDeadWeight 1 loadTimeFunction 1 components 2 0 -10 set 1\n\
         n2slagrangianmultipliercontact 2 loadTimeFunction 1 friction 0.3 slaveset 2 segmentset 1 1\n\
         InitialCondition 1 conditions 1 v 1.0 set 3 dofs 1 1\nConstantFunction 1 f(t) 1\n\
         Set 1 allelements\nSet 2 nodes {} {}\nSet 3 nodes {} {}\n",
        nodes.len(),
        elements.len(),
        nodes.join("\n"),
        elements.join("\n"),
        bottom.len(),
        bottom.join(" "),
        all.len(),
        all.join(" ")
    );
    let model = crate::common::model_from_text(&text).unwrap();
    let (mut slid, mut stopped, mut energy) = (0.0, f64::NAN, Energy::default());
    run_analysis(&model, &crate::common::quiet(), |r| {
        let n = model.nodes.len();
        let mean = |x: &[f64]| {
            (0..n)
                .map(|k| r.dofs.code(k, 1).map_or(0.0, |c| r.dofs.value(x, c)))
                .sum::<f64>()
                / n as f64
        };
        let m = r.motion.unwrap();
        slid = mean(r.u);
        if stopped.is_nan() && mean(m.velocity) < 0.0 {
            stopped = r.time;
        }
        energy = m.energy;
        Ok(())
    })
    .unwrap();
    assert!((slid * 6.0 - 1.0).abs() < 0.02, "slid {slid}");
    assert!((stopped - 1.0 / 3.0).abs() <= 0.02, "stopped at {stopped}");
    // The friction took the kinetic energy (what is left rings in the block).
    let initial = 0.5 * 0.25;
    assert!(
        energy.contact > 0.95 * initial && energy.contact < initial,
        "{energy:?}"
    );
    assert!(energy.balance().abs() < 1e-10, "{energy:?}");
}

/// HHT-α (hertz's `rhoinf` on `ddtScheme 2`): the spring follows the scheme's own recurrence
/// to 1e-12 (m a₁ + (1 + α) k u₁ − α k u₀ = 0 with Newmark's kinematics at γ = ½ − α,
/// β = (1 − α)²/4, computed here), at a resolved step (20 a period: it keeps the energy within
/// 1 % over two periods) and at a step of 20 periods (an unresolved frequency: the energy falls
/// below 1e-3 in 60 steps, after HHT's transient growth, where the trapezoidal rule keeps it).
#[test]
fn hht_follows_its_recurrence_and_damps_high_frequencies_to_rhoinf() {
    let (m, k, u0) = (0.5f64, 100.0f64, 0.01f64);
    let rho = 0.8f64;
    let alpha = (rho - 1.0) / (rho + 1.0);
    let (gamma, beta) = (0.5 - alpha, 0.25 * (1.0 - alpha) * (1.0 - alpha));
    let period = 2.0 * std::f64::consts::PI / (k / m).sqrt();
    for (dt, steps) in [(period / 20.0, 40), (20.0 * period, 60)] {
        let h = history(&spring(&format!("ddtScheme 2 rhoinf {rho}"), steps, dt));
        let (mut u, mut v, mut a) = (u0, 0.0, -k * u0 / m);
        for (t, hu, e) in &h {
            let un =
                (m * (u + dt * v) / (beta * dt * dt) + m * (0.5 / beta - 1.0) * a + alpha * k * u)
                    / (m / (beta * dt * dt) + (1.0 + alpha) * k);
            let an = (un - u - dt * v) / (beta * dt * dt) - (0.5 / beta - 1.0) * a;
            v += dt * ((1.0 - gamma) * a + gamma * an);
            (u, a) = (un, an);
            assert!((hu - u).abs() < 1e-12 * u0, "dt {dt}, t {t}: {hu} vs {u}");
            assert!(e.balance().is_finite());
        }
        let e0 = 0.5 * k * u0 * u0;
        let ratio = mechanical(&h.last().unwrap().2) / e0;
        if dt > period {
            assert!(ratio < 1e-3, "{ratio}");
            let trapezoid = history(&spring("ddtScheme 2", steps, dt));
            assert!((mechanical(&trapezoid.last().unwrap().2) / e0 - 1.0).abs() < 1e-10);
        } else {
            assert!(ratio < 1.0 && ratio > 0.99, "{ratio}");
        }
    }
}
