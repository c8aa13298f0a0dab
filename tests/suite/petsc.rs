//! `hertz run --petsc` (the `petsc` feature: `cargo test --release --features petsc --test suite
//! petsc`): PETSc's CG + GAMG and MUMPS give the answers of hertz's own solvers, on one process
//! and under `mpirun -n 2`; bad PETSc options and a singular model are clear errors. Each run is
//! a process of its own (PETSc and MPI are initialized once per process).

use crate::common;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `hertz run FILE -o DIR ARGS` (quiet unless ARGS has `-v`), under `mpirun -n ranks` if
/// ranks > 1.
fn run(file: &str, dir: &Path, args: &[&str], ranks: usize) -> Output {
    let hertz = env!("CARGO_BIN_EXE_hertz");
    let file = root().join(file);
    let mut cmd = if ranks > 1 {
        let mut c = Command::new("mpirun");
        c.args([
            "-n",
            &ranks.to_string(),
            "--bind-to",
            "none",
            "--oversubscribe",
            hertz,
        ]);
        // Root in CI; traffic on the machine only.
        c.env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .env("OMPI_MCA_btl", "self,vader")
            .env("OMPI_MCA_pml", "ob1")
            .env("OMPI_MCA_oob_tcp_if_include", "lo");
        c
    } else {
        Command::new(hertz)
    };
    cmd.arg("run").arg(&file);
    if !args.contains(&"-v") {
        cmd.arg("-q");
    }
    cmd.arg("-o").arg(dir).args(args);
    cmd.output().expect("running hertz")
}

/// The rows of a CSV file as maps from column to value.
fn csv(path: &Path) -> Vec<std::collections::HashMap<String, f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    lines
        .map(|l| {
            header
                .iter()
                .zip(l.split(','))
                .map(|(h, v)| (h.to_string(), v.parse().unwrap()))
                .collect()
        })
        .collect()
}

fn tmp(name: &str) -> common::Scratch {
    common::scratch(&format!("petsc-{name}"))
}

/// A generated input `text` written as `name` in `dir` (made if need be), as a path for [`run`].
fn written(dir: &Path, name: &str, text: &str) -> String {
    std::fs::create_dir_all(dir).unwrap();
    let file = dir.join(name);
    std::fs::write(&file, text).unwrap();
    file.to_str().unwrap().to_string()
}

/// The `columns` of two CSV files within `tol` relative to the largest of their values (a sum of
/// reactions that cancels is round-off in both).
fn same_columns(a: &Path, b: &Path, tol: f64, columns: fn(&str) -> bool) {
    let (a, b) = (csv(a), csv(b));
    assert_eq!(a.len(), b.len());
    let largest = a
        .iter()
        .flat_map(|r| r.iter().filter(|(k, _)| columns(k)).map(|(_, v)| v.abs()))
        .fold(0.0, f64::max);
    for key in a[0].keys().filter(|k| columns(k)) {
        for (x, y) in a.iter().zip(&b) {
            assert!(
                (x[key] - y[key]).abs() <= tol * largest,
                "{key}: {} vs {}",
                x[key],
                y[key]
            );
        }
    }
}

/// Run `file` with hertz's own solver into `dir`/ref, then by PETSc on one process and on two
/// ranks into `dir`/ranks1 and ranks2: each run succeeds with the reference's Newton iterations
/// (its `stem`.steps.csv), and `check(reference, run)` compares what else it must.
fn on_one_and_two_ranks(file: &str, dir: &Path, stem: &str, check: impl Fn(&Path, &Path)) {
    let reference = dir.join("ref");
    assert!(run(file, &reference, &[], 1).status.success());
    let steps = format!("{stem}.steps.csv");
    let its = |d: &Path| -> Vec<f64> {
        csv(&d.join(&steps))
            .iter()
            .map(|r| r["iterations"])
            .collect()
    };
    for ranks in [1, 2] {
        let out_dir = dir.join(format!("ranks{ranks}"));
        let out = run(file, &out_dir, &["--solver", "petsc"], ranks);
        assert!(out.status.success(), "{ranks} ranks: {out:?}");
        assert_eq!(its(&reference), its(&out_dir), "{ranks} ranks");
        check(&reference, &out_dir);
    }
}

/// The cantilever (beam theory check rules) by CG + GAMG on one process and on two ranks: its
/// rules pass and its reactions and displacements equal the sparse Cholesky's to 1e-8.
#[test]
fn cg_with_algebraic_multigrid_solves_the_cantilever_on_one_and_two_ranks() {
    let reference = tmp("cantilever-ref");
    assert!(run("examples/cantilever.in", &reference, &[], 1)
        .status
        .success());
    for ranks in [1, 2] {
        let dir = tmp(&format!("cantilever-{ranks}"));
        let out = run("examples/cantilever.in", &dir, &["--petsc"], ranks);
        assert!(out.status.success(), "{ranks} ranks: {out:?}");
        assert!(String::from_utf8_lossy(&out.stdout).contains("2 passed, 0 failed"));
        same_columns(
            &reference.join("cantilever.steps.csv"),
            &dir.join("cantilever.steps.csv"),
            1e-8,
            |k| k.starts_with("bc"),
        );
    }
}

/// The rigid cylinder pressed into a block (node-to-segment penalty) by MUMPS' LU across two
/// ranks, by MUMPS' LDLᵀ (the default for a symmetric tangent) on one, and by GMRES with
/// BoomerAMG: the same Newton iterations and contact pressures as hertz's solver (to 1e-6: a penalty of 1e7 turns the gaps'
/// round-off into force).
#[test]
fn mumps_solves_penalty_contact_as_hertz_does() {
    let reference = tmp("circle-ref");
    assert!(run("examples/hertz_rigid_circle.in", &reference, &[], 1)
        .status
        .success());
    let lu = [
        "--petsc",
        "--petsc-options",
        "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps",
    ];
    // GMRES + BoomerAMG: the branch guesses solved loosely, the last again from there.
    let amg = [
        "--petsc",
        "--petsc-options",
        "-ksp_type gmres -pc_type hypre",
    ];
    for (ranks, args) in [(2, &lu[..]), (1, &["--petsc"][..]), (1, &amg[..])] {
        let dir = tmp(&format!("circle-{ranks}"));
        let out = run("examples/hertz_rigid_circle.in", &dir, args, ranks);
        assert!(out.status.success(), "{ranks} ranks: {out:?}");
        let steps = |d: &Path| csv(&d.join("hertz_rigid_circle.steps.csv"));
        assert_eq!(
            steps(&reference)[0]["iterations"],
            steps(&dir)[0]["iterations"]
        );
        same_columns(
            &reference.join("hertz_rigid_circle.contact.csv"),
            &dir.join("hertz_rigid_circle.contact.csv"),
            1e-6,
            |_| true,
        );
    }
}

/// An unknown method is refused before anything is solved (exit 2, naming the options); a
/// mechanism is a singular model (exit 3), not a step to cut back.
#[test]
fn bad_petsc_options_and_a_mechanism_are_clear_errors() {
    let dir = tmp("errors");
    let out = run(
        "examples/cantilever.in",
        &dir,
        &["--petsc", "--petsc-options", "-ksp_type bogus"],
        1,
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("`-ksp_type bogus`"));
    assert!(!dir.join("cantilever.out").exists());
    let out = run("tests/data/mechanism.in", &dir, &["--petsc"], 1);
    assert_eq!(out.status.code(), Some(3));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("singular") && !err.contains("halvings"),
        "{err}"
    );
}

/// A PETSc option the run never read is named after it (misspelled: `-ksp_tyep`), one that was
/// read is not (the cantilever's CG + GAMG reads `-pc_gamg_threshold`); the run itself succeeds.
/// Under `mpirun -n 2`, a run without `--petsc` is refused: each process would solve the whole
/// model and write the same files.
#[test]
fn unread_petsc_options_are_named_and_mpirun_needs_petsc() {
    let dir = tmp("unread");
    let out = run(
        "examples/cantilever.in",
        &dir,
        &[
            "-v",
            "--petsc",
            "--petsc-options",
            "-ksp_tyep cg -pc_gamg_threshold 0.01",
        ],
        1,
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let warning = err
        .lines()
        .find(|l| l.contains("never read"))
        .unwrap_or_else(|| panic!("no warning: {err}"));
    assert!(
        warning.contains("-ksp_tyep") && !warning.contains("gamg"),
        "{warning}"
    );
    let out = run("examples/cantilever.in", &dir, &[], 2);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert_eq!(err.matches("without --solver petsc").count(), 1, "{err}");
}

/// The 3D Hertz sphere (node-to-face multipliers) with `--solver petsc`, on one process and on
/// two ranks (which sum their shares of the tangent for it): hertz eliminates the multipliers
/// and PETSc's CG + GAMG solves the reduced system; both take hertz's own Newton iterations and
/// give its reactions to 1e-8.
#[test]
fn the_hertz_sphere_with_multipliers_matches_hertz_on_one_and_two_ranks() {
    let file = "examples/hertz_sphere.in";
    let reference = tmp("sphere-ref");
    assert!(run(file, &reference, &[], 1).status.success());
    for ranks in [1, 2] {
        let dir = tmp(&format!("sphere-{ranks}"));
        let out = run(file, &dir, &["--solver", "petsc", "-v"], ranks);
        assert!(out.status.success(), "{ranks} ranks: {out:?}");
        let log = String::from_utf8_lossy(&out.stderr);
        assert!(
            log.contains("multipliers eliminated through the slave rows (symmetric): 62 of 62"),
            "{log}"
        );
        let steps = |d: &Path| csv(&d.join("hertz_sphere.steps.csv"));
        assert_eq!(
            steps(&reference)[0]["iterations"],
            steps(&dir)[0]["iterations"]
        );
        same_columns(
            &reference.join("hertz_sphere.steps.csv"),
            &dir.join("hertz_sphere.steps.csv"),
            1e-8,
            |k| k.starts_with("bc") && k.contains(".r"),
        );
    }
}

/// On two ranks each assembles its METIS share of the elements (said with `-v`) and PETSc sums
/// the shares: mortar multipliers (the Hertz cylinder) and Coulomb friction (Cattaneo–Mindlin)
/// take hertz's own Newton iterations and give its reactions to 1e-10, and the friction's contact
/// forces to 1e-7 of the largest. So does the friction on one process (the penalty with
/// friction in multiplier form: GMRES on the counterpart, CG + GAMG on its reduced system).
/// The contact forces are a penalty of 1e7 times gaps of 1.4e-8: a difference of 1e-15 in the
/// 0.022 displacement, round-off of two solvers, is 1e-8 in a node's force (measured: 6e-8 of
/// the largest, while the forces' sum, the reaction, agrees to 1e-10).
#[test]
fn two_ranks_assemble_their_shares_and_match_hertz() {
    for (file, stem, all_ranks) in [
        ("examples/hertz_mortar.in", "hertz_mortar", &[2][..]),
        (
            "examples/cattaneo_mindlin.in",
            "cattaneo_mindlin",
            &[1, 2][..],
        ),
    ] {
        let reference = tmp(&format!("{stem}-ref"));
        assert!(run(file, &reference, &[], 1).status.success());
        for &ranks in all_ranks {
            let dir = tmp(&format!("{stem}-{ranks}"));
            let out = run(file, &dir, &["--petsc", "-v"], ranks);
            assert!(out.status.success(), "{stem}: {out:?}");
            let log = String::from_utf8_lossy(&out.stderr);
            assert!(
                ranks == 1 || log.contains("rank 0 assembles") && log.contains("(METIS, 2 parts)"),
                "{log}"
            );
            let steps = |d: &Path| csv(&d.join(format!("{stem}.steps.csv")));
            let its = |d: &Path| -> Vec<f64> { steps(d).iter().map(|r| r["iterations"]).collect() };
            assert_eq!(its(&reference), its(&dir), "{stem}, {ranks} ranks");
            let name = format!("{stem}.steps.csv");
            same_columns(&reference.join(&name), &dir.join(&name), 1e-10, |k| {
                k.starts_with("bc") && k.contains(".r")
            });
            let name = format!("{stem}.contact.csv");
            same_columns(&reference.join(&name), &dir.join(&name), 1e-7, |k| {
                k == "force" || k == "friction"
            });
        }
    }
}

/// An element that inverts does so on the rank that assembles it: every rank cuts the step
/// back with it. The 3D die as wide as the block with a node-to-face penalty (elements invert
/// in step 7, which takes 8 substeps) runs to its end on two ranks and gives hertz's reactions
/// to 1e-9 in every step. Before, the failing rank cut back while the other waited in the
/// residual's sum forever.
#[test]
fn an_element_failing_on_one_rank_cuts_the_step_on_every_rank() {
    let dir = tmp("die");
    let file = &written(
        &dir,
        "die.in",
        &hertz_bench::suite::die_as_wide_as_the_block(
            3,
            false,
            hertz_bench::suite::Law::Penalty(hertz_bench::suite::DIE_PENALTY),
        ),
    );
    let reference = dir.join("ref");
    assert!(run(file, &reference, &[], 1).status.success());
    let two = dir.join("two");
    let mumps = "-ksp_type preonly -pc_type lu -pc_factor_mat_solver_type mumps";
    let out = run(file, &two, &["--petsc", "--petsc-options", mumps], 2);
    assert!(out.status.success(), "{out:?}");
    let substeps = |d: &Path| -> Vec<f64> {
        csv(&d.join("suite.steps.csv"))
            .iter()
            .map(|r| r["substeps"])
            .collect()
    };
    assert!(substeps(&reference)[6] > 1.0 && substeps(&two)[6] > 1.0);
    same_columns(
        &reference.join("suite.steps.csv"),
        &two.join("suite.steps.csv"),
        1e-9,
        |k| k.starts_with("bc") && k.contains(".r"),
    );
}

/// A 3D block of 16 × 16 × 4 bricks pushed obliquely over a rigid plane with friction
/// multipliers (`verify::pushed_block`: 289 slave nodes, four multipliers each, every one sliding
/// in the second step), with `--solver petsc` on one process and on two ranks: both take
/// hertz's own Newton iterations and its reactions to 1e-10. Across ranks hertz rotates the
/// friction forces and condenses their compliant components and PETSc's CG + GAMG solves the
/// reduced system; on one process (below the Krylov threshold) the general elimination's LU,
/// MUMPS', meets a zero pivot and the same counterpart takes over (the run failed before).
#[test]
fn a_block_sliding_with_friction_matches_hertz_on_one_and_two_ranks() {
    let dir = tmp("pushed");
    let file = &written(
        &dir,
        "pushed_block.in",
        &hertz_bench::verify::pushed_block(
            16,
            4,
            "n2slagrangianmultipliercontact 3 loadTimeFunction 1 friction 0.3",
        ),
    );
    on_one_and_two_ranks(file, &dir, "pushed_block", |reference, out| {
        same_columns(
            &reference.join("pushed_block.steps.csv"),
            &out.join("pushed_block.steps.csv"),
            1e-10,
            |k| k.starts_with("bc") && k.contains(".r"),
        )
    });
}

/// The rod dropped on a floor (`examples/rod_impact.in`: implicit dynamics, multipliers) by
/// PETSc on one process and on two ranks: the same iterations and contact forces, and energies
/// equal to hertz's own solver's to 1e-8. (Two ranks crashed before: the inertia's forces were
/// added on the first rank only, and the second took other decisions.)
#[test]
fn an_impact_matches_hertz_on_one_and_two_ranks() {
    let dir = tmp("impact");
    let file = "examples/rod_impact.in";
    on_one_and_two_ranks(file, &dir, "rod_impact", |reference, out| {
        same_columns(
            &reference.join("rod_impact.energy.csv"),
            &out.join("rod_impact.energy.csv"),
            1e-8,
            |k| ["kinetic", "internal", "contact"].contains(&k),
        );
        same_columns(
            &reference.join("rod_impact.contact.csv"),
            &out.join("rod_impact.contact.csv"),
            1e-8,
            |k| k == "force",
        );
    });
}

/// The rubber tube inflated by a follower pressure (3D, `tests/suite/pressure.rs`): a load whose
/// forces are a step's own terms, as the inertia is. On one process and on two ranks PETSc
/// gives hertz's iterations and reactions to 1e-8 (two ranks waited on each other forever
/// before: the load's forces were the first rank's alone).
#[test]
fn a_follower_pressure_matches_hertz_on_one_and_two_ranks() {
    let dir = tmp("follower");
    let (_, models) = crate::pressure::inflated_tube(true);
    let text = &models[2].1;
    let file = &written(&dir, "tube.in", text);
    // Its output files are named after the input's first line.
    let stem = text.lines().next().unwrap().trim_end_matches(".out");
    let steps = format!("{stem}.steps.csv");
    on_one_and_two_ranks(file, &dir, stem, |reference, out| {
        same_columns(&reference.join(&steps), &out.join(&steps), 1e-8, |k| {
            k.starts_with("bc") && k.contains(".r")
        })
    });
}
