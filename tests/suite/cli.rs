//! The `hertz` binary: help, exit codes, and one malformed input file per error class
//! (tests/data/bad, expectations in tests/data/bad/EXPECTED.txt): each must give its specific
//! message with file:line, exit code 2, and write nothing.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn hertz(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hertz"))
        .args(args)
        .output()
        .expect("run hertz")
}

/// `hertz` with `args`, which must succeed (else its stderr is the failure).
fn hertz_ok(args: &[&str]) -> Output {
    let out = hertz(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// How many files in `dir` end in `.ext`.
fn count_files(dir: &Path, ext: &str) -> usize {
    std::fs::read_dir(dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == ext)
        })
        .count()
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn temp_dir(tag: &str) -> common::Scratch {
    common::scratch(&format!("cli-{tag}"))
}

#[test]
fn help_explains_run_and_check() {
    let out = hertz(&["--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        ["run", "check", "import", "plot", "bench", "completions"]
            .iter()
            .all(|c| text.contains(&format!("\n  {c} "))),
        "{text}"
    );
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        &["frobnicate"][..],
        &["run"][..],
        &["check", "a.in", "b.in"][..],
        &[][..],
    ] {
        let out = hertz(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).starts_with("error: "),
            "{args:?}"
        );
    }
}

#[test]
fn missing_file_exits_2() {
    let out = hertz(&["check", "no/such/file.in"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no/such/file.in: cannot read file"));
}

#[test]
fn malformed_inputs_give_their_message_line_and_exit_2() {
    let bad = root().join("tests/data/bad");
    let table = std::fs::read_to_string(bad.join("EXPECTED.txt")).unwrap();
    let mut n = 0;
    for row in table
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let parts: Vec<&str> = row.splitn(3, " | ").collect();
        let (file, line, msg) = (parts[0], parts[1], parts[2]);
        let path = bad.join(file);
        let shown = path.display().to_string();
        let dir = temp_dir(file);
        let out = hertz(&["run", "-q", &shown, "-o", dir.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(
            out.status.code(),
            Some(2),
            "{file}: exit code; stderr: {stderr}"
        );
        let location = if line == "-" {
            format!("{shown}: ")
        } else {
            format!("{shown}:{line}: ")
        };
        assert!(
            stderr.contains(&location),
            "{file}: expected location `{location}` in\n{stderr}"
        );
        assert!(
            stderr.contains(msg),
            "{file}: expected `{msg}` in\n{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{file}: panic");
        assert!(
            !dir.exists() || std::fs::read_dir(&dir).unwrap().next().is_none(),
            "{file}: output written"
        );
        n += 1;
    }
    assert!(n >= 20, "only {n} malformed inputs");
    // Every file in the folder is in the table.
    let files = count_files(&bad, "in");
    assert_eq!(files, n, "every tests/data/bad/*.in has an expectation");
}

/// A mechanism, loaded (inclined bar chain) or not (a block free to rotate about its only support:
/// its Cholesky pivots are round-off, not zero), is exit 3 naming a node, and leaves no files.
#[test]
fn mechanism_is_a_solver_error_naming_the_node_and_writes_nothing() {
    for (file, nodes) in [
        ("mechanism.in", &["node 2 DOF", "node 3 DOF"][..]),
        (
            "unloaded_mechanism.in",
            &[
                "node 2 DOF",
                "node 3 DOF",
                "node 4 DOF",
                "node 5 DOF",
                "node 6 DOF",
            ][..],
        ),
    ] {
        let dir = temp_dir(file);
        let out = hertz(&[
            "run",
            "-q",
            root().join("tests/data").join(file).to_str().unwrap(),
            "-o",
            dir.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(3), "{file}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            nodes
                .iter()
                .any(|n| stderr.contains(&format!("singular at {n}"))),
            "{file}: {stderr}"
        );
        assert!(
            !dir.exists() || std::fs::read_dir(&dir).unwrap().next().is_none(),
            "{file}: output written"
        );
    }
}

#[test]
fn check_reports_rules_and_exits_1_on_a_failed_rule() {
    let src = std::fs::read_to_string(root().join("tests/data/oofem/patch100.in")).unwrap();
    let broken = src.replace(
        "#NODE tStep 1 number 4 dof 1 unknown d value -1.5625",
        "#NODE tStep 1 number 4 dof 1 unknown d value -1.6",
    );
    assert_ne!(src, broken);
    let dir = temp_dir("failrule");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("patch100.in");
    std::fs::write(&path, broken).unwrap();
    let out = hertz(&["check", "-q", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("computed -1.5625000000e+00"), "{stdout}");
    assert!(stdout.contains("expected -1.6000000000e+00"), "{stdout}");
    assert!(
        stdout.trim_end().ends_with("35 passed, 1 failed"),
        "{stdout}"
    );
    assert!(
        !Path::new(&dir.join("patch100.out")).exists(),
        "check writes no .out"
    );
}

/// `--vtu binary` writes raw appended arrays (VTK's header of UInt64 byte counts); `-v` reports
/// the time the output took.
#[test]
fn run_vtu_binary_writes_appended_data_and_verbose_times_the_output() {
    let dir = temp_dir("vtu-binary");
    std::fs::create_dir_all(&dir).unwrap();
    let input = root().join("tests/data/oofem/brick_nlgeo_1.in");
    let out = hertz(&[
        "run",
        "-v",
        "--vtu",
        "binary",
        input.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("output files formatted and written in"),
        "{stderr}"
    );
    let vtu = std::fs::read(dir.join("brick_nlgeo_1.5.vtu")).unwrap();
    let text = String::from_utf8_lossy(&vtu);
    assert!(text.contains("header_type=\"UInt64\""));
    assert!(text.contains("format=\"appended\" offset=\"0\""));
    assert!(!text.contains("format=\"ascii\""));
    // Step 5: every node translated by 2 (see the test below), read back from the bytes.
    let arrays = common::read_vtu(&dir.join("brick_nlgeo_1.5.vtu"));
    assert!(arrays["displacement"].iter().all(|&u| u == 2.0));
    let bad = hertz(&["run", "--vtu", "base64", input.to_str().unwrap()]);
    assert_eq!(bad.status.code(), Some(2));
}

#[test]
fn run_writes_out_vtu_and_pvd_next_to_the_input() {
    let dir = temp_dir("run");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(
        root().join("tests/data/oofem/brick_nlgeo_1.in"),
        dir.join("b.in"),
    )
    .unwrap();
    hertz_ok(&["run", "-q", dir.join("b.in").to_str().unwrap()]);
    let text = std::fs::read_to_string(dir.join("brick_nlgeo_1.out")).unwrap();
    // Step 5: all nodes translated by 0.5·(f(5) = 4) = 2 in every direction.
    assert!(text.contains("  dof 3   d  2.00000000e+00"), "{text}");
    assert_eq!(text.matches("Output for time").count(), 5);
    for k in 1..=5 {
        assert!(dir.join(format!("brick_nlgeo_1.{k}.vtu")).is_file());
    }
    let pvd = std::fs::read_to_string(dir.join("brick_nlgeo_1.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 5);
    assert!(std::fs::read_dir(&dir).unwrap().all(|e| !e
        .unwrap()
        .file_name()
        .to_string_lossy()
        .contains(".tmp")));
}

/// A UTF-8 byte-order mark is skipped (it used to end up in the output file names).
#[test]
fn byte_order_mark_is_skipped() {
    let src = std::fs::read(root().join("tests/data/oofem/patch100.in")).unwrap();
    let dir = temp_dir("bom");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bom.in");
    std::fs::write(&path, [&b"\xEF\xBB\xBF"[..], &src].concat()).unwrap();
    hertz_ok(&["run", "-q", path.to_str().unwrap()]);
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(names.iter().any(|n| n == "patch100.out"), "{names:?}");
    assert!(names.iter().all(|n| n.is_ascii()), "{names:?}");
}

/// Unread tokens are reported in a short line, and an error's record is cut, however long the
/// record is; -q silences the warning.
#[test]
fn long_records_are_reported_shortly() {
    let src = std::fs::read_to_string(root().join("tests/data/oofem/patch100.in")).unwrap();
    let junk: String = (0..200_000).map(|i| format!(" junk{i}")).collect();
    let dir = temp_dir("long");
    std::fs::create_dir_all(&dir).unwrap();
    let (first, rest) = src.split_once("\nnode ").unwrap();
    let path = dir.join("long.in");
    std::fs::write(
        &path,
        format!(
            "{first}\nnode {}",
            rest.replacen('\n', &format!("{junk}\n"), 1)
        ),
    )
    .unwrap();
    let out = hertz(&["check", path.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let warning = stderr
        .lines()
        .find(|l| l.contains("unread"))
        .expect("warning");
    assert!(warning.contains("and 199994 more"), "{warning}");
    assert!(warning.len() < 300, "{} characters", warning.len());
    let quiet = hertz(&["check", "-q", path.to_str().unwrap()]);
    assert!(
        quiet.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&quiet.stderr)
    );
    // The same record with a bad number: the error shows 160 characters of it.
    let bad = dir.join("bad.in");
    std::fs::write(
        &bad,
        std::fs::read_to_string(&path).unwrap().replacen(
            "node 1 coords 3  0.0   0.0",
            "node 1 coords 3  0.0   x.0",
            1,
        ),
    )
    .unwrap();
    let out = hertz(&["check", bad.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.len() < 2000, "{} bytes of message", stderr.len());
    assert!(stderr.contains("more characters"), "{stderr}");
}

/// Absurd benchmark sizes are refused at once (exit 2), before anything is generated.
#[test]
fn absurd_bench_sizes_are_refused_before_allocating() {
    for args in [
        &["bench", "--n", "1000000"][..],
        &["bench", "--dim", "3", "--n", "500"][..],
        &["bench", "--n", "0"][..],
        &["bench", "--patch", "1000"][..],
        &["bench", "--sphere", "0.001"][..],
    ] {
        let t = std::time::Instant::now();
        let out = hertz(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("error"),
            "{args:?}"
        );
        assert!(
            t.elapsed().as_secs_f64() < 5.0,
            "{args:?} took {:?}",
            t.elapsed()
        );
    }
}

/// `hertz bench --write DIR` writes the plain block too (for `hertz run --petsc` beyond the
/// direct solver's size), and the file runs to the exact uniaxial field: the rollers' reaction on
/// x = 0 balances the traction 100 on the 3 × 3 face x = 3.
#[test]
fn a_written_bench_block_runs_to_its_exact_reaction() {
    let dir = temp_dir("bench-write");
    hertz_ok(&[
        "bench",
        "--dim",
        "3",
        "--n",
        "3",
        "--write",
        dir.to_str().unwrap(),
    ]);
    let file = dir.join("block3d_3.in");
    hertz_ok(&["run", "-q", file.to_str().unwrap()]);
    let csv = std::fs::read_to_string(dir.join("block.steps.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = header.iter().position(|h| *h == "bc1.r1").expect("bc1.r1");
    let r: f64 = row[at].parse().unwrap();
    assert!((r + 900.0).abs() < 1e-9, "reaction {r}");
}

/// `hertz bench --ironing3d LAYERS --write DIR` writes the shallow ironing benchmark's published
/// mesh (120 × 20 block, 12 × 4 die) extruded to LAYERS bricks through the depth: its nodes and
/// elements, and the die's arc (12 × LAYERS faces) as the mortar slave.
#[test]
fn bench_writes_the_shallow_ironing_extruded_to_3d() {
    let dir = temp_dir("bench-ironing");
    hertz_ok(&[
        "bench",
        "--ironing3d",
        "2",
        "--write",
        dir.to_str().unwrap(),
    ]);
    let model = hertz::input::read_model(&dir.join("shallow_ironing3d.in"))
        .unwrap()
        .model;
    assert_eq!(model.nodes.len(), 121 * 3 * 21 + 13 * 3 * 5);
    assert_eq!(model.elements.len(), 120 * 2 * 20 + 12 * 2 * 4);
    let faces = |k: usize| match &model.segments[k].kind {
        hertz::model::SegmentKind::Faces { faces } => faces.len(),
        other => panic!("segment {k}: {other:?}"),
    };
    assert_eq!((faces(0), faces(1)), (120 * 2, 12 * 2));
}

#[test]
fn version_and_completions() {
    let out = hertz(&["--version"]);
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout).trim(),
        format!("hertz {}", env!("CARGO_PKG_VERSION"))
    );
    let out = hertz(&["completions", "bash"]);
    assert!(out.status.success());
    let script = String::from_utf8_lossy(&out.stdout);
    assert!(
        script.contains("complete") && script.contains("import"),
        "{script}"
    );
}

/// An input whose first line names the input itself (or a file it includes) is refused before
/// anything is solved or written: exit 2, the reason, and the input intact.
#[test]
fn run_never_overwrites_its_input() {
    let dir = temp_dir("own-input");
    std::fs::create_dir_all(&dir).unwrap();
    let example = std::fs::read_to_string(root().join("examples/cantilever.in")).unwrap();
    let body = example.split_once('\n').unwrap().1;
    for (name, first_line) in [("self.in", "self.in"), ("main.in", "part.in")] {
        let text = format!("{first_line}\n{body}");
        let path = dir.join(name);
        std::fs::write(&path, &text).unwrap();
        // The second case names an included file: the mesh lives in part.in.
        let text = if name == "main.in" {
            let (head, rest) = text.split_once("node 1 coords").unwrap();
            std::fs::write(dir.join("part.in"), format!("node 1 coords{rest}")).unwrap();
            let t = format!("{head}@include \"part.in\"\n");
            std::fs::write(&path, &t).unwrap();
            t
        } else {
            text
        };
        let out = hertz(&["run", "-q", path.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains(&format!(
                "would overwrite its input file {}",
                dir.join(first_line).display()
            )),
            "{stderr}"
        );
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            text,
            "input intact"
        );
        let written: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .filter(|n| !n.ends_with(".in"))
            .collect();
        assert!(written.is_empty(), "nothing written: {written:?}");
    }
}

/// `hertz import` writes over no file it did not write: the default `mesh.in` beside a user's
/// input of that name is refused (exit 2, the file intact); its own earlier output is renewed.
#[test]
fn import_never_overwrites_a_users_file() {
    let dir = temp_dir("import-keep");
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = dir.join("square.msh");
    std::fs::copy(root().join("tests/data/gmsh/square_tri.msh"), &mesh).unwrap();
    let users = dir.join("square.in");
    std::fs::write(&users, "my own model\n").unwrap();
    let out = hertz(&["import", mesh.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("exists and was not written by `hertz import`"),
        "{stderr}"
    );
    assert_eq!(std::fs::read_to_string(&users).unwrap(), "my own model\n");
    let target = dir.join("square_mesh.in");
    for _ in 0..2 {
        hertz_ok(&[
            "import",
            mesh.to_str().unwrap(),
            "-o",
            target.to_str().unwrap(),
        ]);
    }
    assert!(std::fs::read_to_string(&target)
        .unwrap()
        .starts_with("# Converted by hertz"));
    let out = hertz(&[
        "import",
        mesh.to_str().unwrap(),
        "-o",
        mesh.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(std::fs::read_to_string(&mesh)
        .unwrap()
        .contains("$MeshFormat"));
}

/// A warning about an unread token comes before the solver's error, when the typo is the likely
/// cause, and also before a reader error.
#[test]
fn warnings_come_before_a_failure() {
    let dir = temp_dir("warn-first");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(root().join("tests/data/mechanism.in")).unwrap();
    let typo = text.replacen(
        "StaticStructural nsteps 1",
        "StaticStructural nsteps 1 maxitr 20",
        1,
    );
    let broken = typo.replacen("Truss2d 3 nodes 2 3 4", "Truss2d 3 nodes 2 3 9", 1);
    assert_ne!(broken, typo, "the element record to break is there");
    for (name, text, exit) in [("solve.in", &typo, 3), ("read.in", &broken, 2)] {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let out = hertz(&["run", path.to_str().unwrap(), "-o", dir.to_str().unwrap()]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(exit), "{stderr}");
        let warning = stderr.find("unread token(s) `maxitr 20`").expect(&stderr);
        let error = stderr.find("error:").expect(&stderr);
        assert!(warning < error, "the warning first: {stderr}");
    }
}

/// A body that only frictionless contact holds, pushed sideways, is a mechanism: exit 3 at once
/// (no step halvings) naming a node's DOF 1, with a penalty and with multipliers. The same block
/// pressed without the push (a consistent singular tangent), or held by friction, solves.
#[test]
fn a_contact_mechanism_is_named_at_once() {
    let text = std::fs::read_to_string(root().join("tests/data/contact_mechanism.in")).unwrap();
    let multipliers = text.replace("n2spenaltycontact", "n2slagrangianmultipliercontact");
    let dir = temp_dir("contact-mechanism");
    std::fs::create_dir_all(&dir).unwrap();
    let run = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        hertz(&["check", path.to_str().unwrap()])
    };
    for (name, text) in [("penalty.in", &text), ("multipliers.in", &multipliers)] {
        let out = run(name, text);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(3), "{name}: {stderr}");
        assert!(
            stderr.contains("the tangent with the contact's stiffness is singular at node")
                && stderr.contains("DOF 1: a mechanism"),
            "{name}: {stderr}"
        );
        assert!(
            !stderr.contains("halving") && !stderr.contains("retrying"),
            "{stderr}"
        );
    }
    let unpushed = text.replace("components 2 0.1 0", "components 2 0 0");
    let held = multipliers.replace("segmentset 1 1", "segmentset 1 1 friction 0.3");
    for (name, text) in [("unpushed.in", &unpushed), ("held.in", &held)] {
        let out = run(name, text);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// Every example command of `hertz --help` parses as written: run where its files do not exist,
/// it fails on the missing file, never with a usage error.
#[test]
fn help_examples_parse_as_written() {
    let out = hertz(&["--help"]);
    let help = String::from_utf8_lossy(&out.stdout).to_string();
    let dir = temp_dir("help-examples");
    std::fs::create_dir_all(&dir).unwrap();
    let mut n = 0;
    for line in help
        .lines()
        .filter(|l| l.trim_start().starts_with("hertz "))
    {
        // The command is the words up to a run of two spaces (the description).
        let cmd = line.trim_start().split("  ").next().unwrap();
        let args: Vec<&str> = cmd.split_whitespace().skip(1).collect();
        let out = Command::new(env!("CARGO_BIN_EXE_hertz"))
            .args(&args)
            .current_dir(&dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            !stderr.contains("Usage:"),
            "`{cmd}` is not valid usage: {stderr}"
        );
        n += 1;
    }
    assert!(n >= 4, "{help}");
}

/// The per-step history's columns follow the boundary conditions' numbers, then the DOF ids, not
/// the order their nodes come in.
#[test]
fn steps_csv_columns_follow_the_condition_numbers() {
    let text = "plate.out\nplate\nLinearStatic nsteps 1\ndomain 2dPlaneStress\nOutputManager\n\
        ndofman 4 nelem 1 ncrosssect 1 nmat 1 nbc 3 nic 0 nltf 1 nset 4\n\
        node 1 coords 2 0 0\nnode 2 coords 2 1 0\nnode 3 coords 2 1 1\nnode 4 coords 2 0 1\n\
        PlaneStress2d 1 nodes 4 1 2 3 4\nSimpleCS 1 thick 1 material 1 set 1\n\
        IsoLE 1 d 0 E 100 n 0.3 tAlpha 0\n\
        BoundaryCondition 1 loadTimeFunction 1 dofs 2 2 1 values 2 0.01 0 set 2\n\
        BoundaryCondition 2 loadTimeFunction 1 dofs 1 2 values 1 0 set 3\n\
        BoundaryCondition 3 loadTimeFunction 1 dofs 1 1 values 1 0 set 4\n\
        ConstantFunction 1 f(t) 1.0\n\
        Set 1 allelements\nSet 2 nodes 1 3\nSet 3 nodes 2 1 2\nSet 4 nodes 1 4\n";
    let dir = temp_dir("steps-order");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("plate.in");
    std::fs::write(&path, text).unwrap();
    hertz_ok(&["run", "-q", path.to_str().unwrap()]);
    let csv = std::fs::read_to_string(dir.join("plate.steps.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "step,time,iterations,substeps,residual,bc1.u1,bc1.r1,bc1.u2,bc1.r2,bc2.u2,bc2.r2,bc3.u1,bc3.r1"
    );
}

/// An unknown condition record lists every supported one, mortar and upstream records included
/// (the list comes from the reader's keyword tables).
#[test]
fn unknown_condition_lists_every_supported_record() {
    let text = std::fs::read_to_string(root().join("tests/data/bad/unknown_load.in")).unwrap();
    let Err(err) = hertz::input::read_model_str(&text, "unknown_load.in") else {
        panic!("an unknown record is an error");
    };
    let err = err.to_string();
    for kw in [
        "DeadWeight",
        "n2slagrangianmultipliercontact",
        "s2spenaltycontact",
        "s2slagrangianmultipliercontact",
        "StructuralPenaltyContactBC",
    ] {
        assert!(err.contains(kw), "{kw}: {err}");
    }
    assert!(!err.contains("ConstantPressureLoad"), "{err}");
    assert!(err.starts_with("unknown_load.in:21:"), "{err}");
}

/// The VTU files follow the output manager's step selection where it makes one (`tstep_step 26`
/// on the dropped rod's 104 steps: steps 26, 52, 78 and 104, and the PVD lists those), and are
/// written at every step where it makes none.
#[test]
fn vtu_files_are_written_at_the_selected_steps() {
    let scratch = common::scratch("vtu-steps");
    let dir: &Path = scratch.as_ref();
    std::fs::create_dir_all(dir).unwrap();
    let text = std::fs::read_to_string(root().join("examples/rod_impact.in")).unwrap();
    for (manager, expected) in [("OutputManager tstep_step 26", 4), ("OutputManager", 104)] {
        let input = dir.join("rod.in");
        std::fs::write(&input, text.replace("OutputManager tstep_all", manager)).unwrap();
        let out = dir.join(format!("out{expected}"));
        hertz_ok(&[
            "run",
            "-q",
            input.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        let vtus = count_files(&out, "vtu");
        assert_eq!(vtus, expected, "{manager}");
        let pvd = std::fs::read_to_string(out.join("rod_impact.pvd")).unwrap();
        assert_eq!(pvd.matches("<DataSet").count(), expected, "{manager}");
        if expected == 4 {
            assert!(
                out.join("rod_impact.26.vtu").is_file() && out.join("rod_impact.104.vtu").is_file()
            );
        }
    }
}

/// Started by an MPI launcher as several processes without `--solver petsc`, every process
/// would solve the whole model and write the same files (issue 50 item 10): each refuses with
/// exit code 2 and writes nothing, and only the first says why. Open MPI's and MPICH's variables.
#[test]
fn several_mpi_processes_without_petsc_are_refused() {
    let scratch = temp_dir("mpi-without-petsc");
    let dir: &Path = scratch.as_ref();
    std::fs::create_dir_all(dir).unwrap();
    let input = root().join("examples/cantilever.in");
    for (size, rank) in [
        ("OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"),
        ("PMI_SIZE", "PMI_RANK"),
    ] {
        for r in ["0", "1"] {
            let out = Command::new(env!("CARGO_BIN_EXE_hertz"))
                .args(["run", "-q", "-o"])
                .arg(dir)
                .arg(&input)
                .env(size, "2")
                .env(rank, r)
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{size} rank {r}: {err}");
            assert_eq!(err.contains("without --solver petsc"), r == "0", "{err}");
            assert_eq!(count_files(dir, "out"), 0);
        }
    }
    // One process under a launcher runs as usual.
    let out = Command::new(env!("CARGO_BIN_EXE_hertz"))
        .args(["run", "-q", "-o"])
        .arg(dir)
        .arg(&input)
        .env("OMPI_COMM_WORLD_SIZE", "1")
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(count_files(dir, "out"), 1);
}
