//! The laws' tangents against finite differences in every stress mode, and their answers against
//! closed forms: the uniaxial cycle, kinematic hardening's reversed yield, OOFEM's table and
//! damage, finite-strain uniaxial tension and the small-strain limit.

use super::finite_strain::LogStrainMises;
use super::small_strain::SmallStrainMises;
use super::*;
use crate::material::law::respond_into;
use crate::model::{Damage, Hardening, Mises, StressMode};

fn steel(hardening: Hardening, kinematic: f64, damage: Option<Damage>) -> Mises {
    Mises {
        young: 210.0,
        poisson: 0.3,
        hardening,
        kinematic,
        damage,
    }
}

fn linear(sig0: f64, modulus: f64) -> Hardening {
    Hardening::Linear { sig0, modulus }
}

/// The law's stress, tangent and new state at `strain` from `old`.
fn respond(law: &dyn PointLaw, strain: &[f64], old: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = law.components();
    let (mut s, mut t, mut st) = (vec![0.0; n], vec![0.0; n * n], vec![0.0; law.state_len()]);
    respond_into(law, strain, old, (&mut s, &mut t, &mut st)).unwrap();
    (s, t, st)
}

/// The worst difference between the tangent and central differences of the stress, relative
/// to the tangent's largest entry.
fn tangent_error(law: &dyn PointLaw, strain: &[f64], old: &[f64], h: f64) -> f64 {
    let n = law.components();
    let (_, t, _) = respond(law, strain, old);
    let scale = t.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let mut worst = 0.0f64;
    for j in 0..n {
        let (mut p, mut m) = (strain.to_vec(), strain.to_vec());
        p[j] += h;
        m[j] -= h;
        let (sp, _, _) = respond(law, &p, old);
        let (sm, _, _) = respond(law, &m, old);
        for i in 0..n {
            let fd = (sp[i] - sm[i]) / (2.0 * h);
            worst = worst.max((fd - t[i * n + j]).abs() / scale);
        }
    }
    worst
}

/// A state the law reaches by a plastic strain path (so the committed state is not virgin).
fn loaded_state(law: &dyn PointLaw, path: &[Vec<f64>]) -> Vec<f64> {
    let mut state = vec![0.0; law.state_len()];
    law.initial_state(&mut state);
    for strain in path {
        state = respond(law, strain, &state).2;
    }
    state
}

/// A strain of the mode's components from a full-Voigt one.
fn reduced(mode: StressMode, full: &[f64; 6]) -> Vec<f64> {
    crate::material::voigt_components(mode)
        .iter()
        .map(|&c| full[c])
        .collect()
}

fn laws(m: &Mises, mode: StressMode) -> Vec<(&'static str, Box<dyn PointLaw>)> {
    let mut v: Vec<(&'static str, Box<dyn PointLaw>)> = vec![(
        "small strain",
        Box::new(InMode {
            law: SmallStrainMises { params: m.clone() },
            mode,
        }),
    )];
    if m.kinematic == 0.0 && mode != StressMode::Uniaxial {
        v.push((
            "finite strain",
            Box::new(InMode {
                law: LogStrainMises { params: m.clone() },
                mode,
            }),
        ));
    }
    v
}

#[test]
fn tangents_are_the_derivatives_of_the_stress_in_every_mode_elastic_and_plastic() {
    let table = Hardening::Table {
        kappa: vec![0.0, 0.004, 0.05],
        stress: vec![0.3, 0.5, 0.6],
    };
    let materials = [
        steel(linear(0.3, 10.0), 0.0, None),
        steel(table, 0.0, None),
        steel(linear(0.3, 5.0), 8.0, None),
        steel(
            linear(0.3, 10.0),
            0.0,
            Some(Damage {
                critical: 0.3,
                rate: 50.0,
            }),
        ),
    ];
    // A first plastic load, then strains beyond (plastic) and back (elastic unloading).
    let first = [0.004, -0.001, -0.0015, 0.002, -0.001, 0.003];
    let beyond = [0.007, -0.002, -0.002, 0.003, -0.0012, 0.005];
    let back = [0.003, -0.0008, -0.0012, 0.0015, -0.0008, 0.0025];
    for m in &materials {
        for mode in [
            StressMode::ThreeD,
            StressMode::PlaneStrain,
            StressMode::PlaneStress,
            StressMode::Uniaxial,
        ] {
            for (name, law) in laws(m, mode) {
                let old = loaded_state(law.as_ref(), &[reduced(mode, &first)]);
                for (what, strain) in [("plastic", &beyond), ("elastic", &back)] {
                    let e = tangent_error(law.as_ref(), &reduced(mode, strain), &old, 1e-8);
                    assert!(
                        e < 2e-6,
                        "{name} {mode:?} {what} {m:?}: tangent error {e:.2e}"
                    );
                }
            }
        }
    }
}

#[test]
fn finite_strain_tangents_hold_at_large_strains_and_are_symmetric() {
    let m = steel(linear(0.3, 2.0), 0.0, None);
    let law = InMode {
        law: LogStrainMises { params: m },
        mode: StressMode::ThreeD,
    };
    let first = [0.25, -0.1, -0.08, 0.2, -0.05, 0.3];
    let old = loaded_state(&law, &[first.to_vec()]);
    let strain = [0.4, -0.12, -0.15, 0.25, -0.1, 0.45];
    let e = tangent_error(&law, &strain, &old, 1e-7);
    assert!(e < 1e-6, "tangent error {e:.2e}");
    let (_, t, _) = respond(&law, &strain, &old);
    let scale = t.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    for i in 0..6 {
        for j in 0..i {
            assert!(
                (t[i * 6 + j] - t[j * 6 + i]).abs() < 1e-9 * scale,
                "D[{i}][{j}] {} against D[{j}][{i}] {}",
                t[i * 6 + j],
                t[j * 6 + i]
            );
        }
    }
}

/// A bar pulled past yield, unloaded, compressed past yield and reloaded: σ and ε_p exact at
/// every point of the cycle, with isotropic hardening (the reversed yield at −σ_y(κ)) and with
/// kinematic (at β − σ₀, the Bauschinger effect).
#[test]
fn a_uniaxial_cycle_follows_the_closed_form() {
    let (e, s0) = (210.0, 0.3);
    for (h, hk) in [(10.0, 0.0), (0.0, 10.0), (4.0, 6.0)] {
        let m = steel(linear(s0, h), hk, None);
        let law = InMode {
            law: SmallStrainMises { params: m },
            mode: StressMode::Uniaxial,
        };
        let mut state = loaded_state(&law, &[]);
        // The closed form: ε_p, κ, β and σ along the path.
        let (mut ep, mut kappa, mut beta) = (0.0f64, 0.0f64, 0.0f64);
        for eps in [0.001, 0.003, 0.005, 0.002, 0.0, -0.004, -0.006, 0.0, 0.008] {
            let trial = e * (eps - ep);
            let f = (trial - beta).abs() - (s0 + h * kappa);
            if f > 0.0 {
                let dk = f / (e + h + hk);
                let sign = (trial - beta).signum();
                ep += dk * sign;
                kappa += dk;
                beta += hk * dk * sign;
            }
            let sigma = e * (eps - ep);
            let (s, _, new) = respond(&law, &[eps], &state);
            state = new;
            assert!(
                (s[0] - sigma).abs() < 1e-12 * e,
                "H {h}, Hk {hk}, ε {eps}: σ {} against {sigma}",
                s[0]
            );
            let p = law.plastic(&state).unwrap();
            assert!(
                (p.strain[0] - ep).abs() < 1e-14,
                "ε_p {} against {ep}",
                p.strain[0]
            );
            assert!(
                (p.kappa - kappa).abs() < 1e-14,
                "κ {} against {kappa}",
                p.kappa
            );
            // Isochoric: the lateral plastic strains are −ε_p/2.
            assert!((p.strain[1] + 0.5 * ep).abs() < 1e-14);
        }
    }
}

/// OOFEM's tests Mises02 (table hardening then softening) and Mises01 (damage): the stress of
/// their single bar at the steps their check rules give.
#[test]
fn oofem_table_and_damage_tests_give_their_stresses() {
    let bar = |m: Mises| InMode {
        law: SmallStrainMises { params: m },
        mode: StressMode::Uniaxial,
    };
    let mises02 = bar(Mises {
        young: 1.0,
        poisson: 0.2,
        hardening: Hardening::Table {
            kappa: vec![0.0, 3.0, 25.0],
            stress: vec![1.0, 2.0, 1.0],
        },
        kinematic: 0.0,
        damage: None,
    });
    // Steps 1–3 of a bar of length 0.5 stretched by 12/11 per step.
    let mut state = loaded_state(&mises02, &[]);
    let mut sigma = 0.0;
    for step in 1..=3 {
        let eps = 12.0 / 11.0 * step as f64 / 0.5;
        let (s, _, new) = respond(&mises02, &[eps], &state);
        (sigma, state) = (s[0], new);
    }
    assert!((sigma - 1.9264).abs() < 1e-4, "Mises02 step 3: σ {sigma}");
    let mises01 = bar(Mises {
        young: 1.0,
        poisson: 0.2,
        hardening: linear(1.0, 0.1),
        kinematic: 0.0,
        damage: Some(Damage {
            critical: 0.1,
            rate: 0.1,
        }),
    });
    // The end displacement 0.4·f(t), f piecewise linear through (1, 0), (6, 5), (11, −5),
    // (16, 5), (21, −5): ε = 0.8·f(t).
    let f = |t: f64| {
        let pts = [
            (1.0, 0.0),
            (6.0, 5.0),
            (11.0, -5.0),
            (16.0, 5.0),
            (21.0, -5.0),
        ];
        let i = pts.windows(2).position(|w| t <= w[1].0).unwrap();
        let ((t0, f0), (t1, f1)) = (pts[i], pts[i + 1]);
        f0 + (f1 - f0) * (t - t0) / (t1 - t0)
    };
    let mut state = loaded_state(&mises01, &[]);
    for (step, expected) in (1..=20).map(|s| (s, [(6, 1.2423), (20, -2.1853)])) {
        let (s, _, new) = respond(&mises01, &[0.8 * f(step as f64)], &state);
        state = new;
        for (at, value) in expected {
            if step == at {
                assert!(
                    (s[0] - value).abs() < 1e-4,
                    "Mises01 step {step}: σ {}",
                    s[0]
                );
            }
        }
    }
}

/// Uniaxial tension of the finite-strain law to a stretch of 1.6: with Hencky elasticity the
/// Kirchhoff stress is τ = σ₀ + H·ε_p on the logarithmic strain ε = ln λ = τ/E + ε_p, so
/// S₁₁ = τ/λ² exactly; and at strains of 10⁻⁶ the law is the small-strain one.
#[test]
fn finite_strain_uniaxial_tension_is_exact_and_small_strains_are_small_strain() {
    let (e, s0, h) = (210.0, 0.3, 3.0);
    let m = steel(linear(s0, h), 0.0, None);
    let law = InMode {
        law: LogStrainMises { params: m.clone() },
        mode: StressMode::Uniaxial,
    };
    let mut state = loaded_state(&law, &[]);
    for stretch in [1.0005, 1.001, 1.01, 1.1, 1.3, 1.6] {
        let green = 0.5 * (stretch * stretch - 1.0);
        let (s, _, new) = respond(&law, &[green], &state);
        state = new;
        let log = f64::ln(stretch);
        let tau = if e * log > s0 {
            let ep = (e * log - s0) / (e + h);
            s0 + h * ep
        } else {
            e * log
        };
        let expected = tau / (stretch * stretch);
        assert!(
            (s[0] - expected).abs() < 1e-10 * expected,
            "λ {stretch}: S {} against {expected}",
            s[0]
        );
    }
    let small = InMode {
        law: SmallStrainMises { params: m.clone() },
        mode: StressMode::ThreeD,
    };
    let finite = InMode {
        law: LogStrainMises { params: m },
        mode: StressMode::ThreeD,
    };
    // Elastic strains of 10⁻⁶, and plastic ones of 3·10⁻³ (yield at 1.4·10⁻³): the two laws
    // differ by terms of the strain's order relative to the stress.
    let strain: Vec<f64> = [3.0, -1.0, -0.5, 2.0, 1.0, -1.5]
        .iter()
        .map(|v| v * 1e-6)
        .collect();
    let plastic: Vec<f64> = strain.iter().map(|v| v * 1e3).collect();
    for eps in [&strain, &plastic] {
        let (a, _, _) = respond(&small, eps, &loaded_state(&small, &[]));
        let (b, _, _) = respond(&finite, eps, &loaded_state(&finite, &[]));
        let size = a.iter().fold(0.0f64, |x, v| x.max(v.abs()));
        let strain_size = eps.iter().fold(0.0f64, |x, v| x.max(v.abs()));
        for i in 0..6 {
            assert!(
                (a[i] - b[i]).abs() < 10.0 * strain_size * size,
                "component {i}: {} against {}",
                b[i],
                a[i]
            );
        }
    }
}
