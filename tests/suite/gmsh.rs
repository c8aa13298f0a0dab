//! Gmsh meshes (tests/data/gmsh, made by box.py; examples/gmsh): every element type hertz maps
//! passes a patch test (uniform compression, exact displacement field) after conversion, in both
//! file formats, with mirrored elements turned right; `hertz import` writes what `@gmsh` reads;
//! the Hertz example meshed in Gmsh meets the analytical solution.

use crate::common;

use hertz::mesh::gmsh::{convert, Plane};
use hertz::output::vtu::VtuFormat;
use hertz::solve::run_analysis;
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gmsh")
        .join(name)
}

const STRAIN: f64 = -0.01;
const NU: f64 = 0.3;

/// Compress the body meshed in `mesh` by 1 % along its last axis (rollers on the planes x = 0,
/// y = 0, bottom; the top prescribed) and return the worst nodal error against the exact field
/// u_top = ε·z, u_lateral = −ν·ε·x (in 2D plane stress; −ν/(1−ν)·ε·x in plane strain).
fn patch_error(mesh: &Path, plane: Plane) -> f64 {
    let c = convert(mesh, plane).unwrap();
    let lateral = if c.dim == 2 && plane == Plane::Strain {
        NU / (1.0 - NU)
    } else {
        NU
    };
    let strain = match plane {
        Plane::Strain => " plane strain",
        Plane::Axisymmetric => " axisymmetric",
        Plane::Stress => "",
    };
    let text = patch_input(&c, &format!("@gmsh \"{}\"{strain}", mesh.display()));
    let model = common::model_from_text(&text).unwrap();
    let dim = c.dim;
    let mut worst = f64::NAN;
    run_analysis(&model, &common::quiet(), |r| {
        worst = 0.0;
        for (n, node) in model.nodes.iter().enumerate() {
            let x = node.coords;
            for d in 1..=dim as u8 {
                let exact = if d as usize == dim {
                    STRAIN * x[dim - 1]
                } else {
                    -lateral * STRAIN * x[d as usize - 1]
                };
                let u = r.displacement(n, d).unwrap();
                worst = worst.max((u - exact).abs());
            }
        }
        Ok(())
    })
    .unwrap();
    worst
}

/// The patch-test input of the converted mesh `c`, whose records `mesh` gives (an `@gmsh` line
/// or the records themselves).
fn patch_input(c: &hertz::mesh::gmsh::Converted, mesh: &str) -> String {
    let (dim, nset) = (c.dim, c.sets.len());
    let set = |name: &str| c.sets.iter().find(|s| s.name == name).unwrap().number;
    let (domain, lateral) = if dim == 3 {
        (
            "3d",
            format!(
                "BoundaryCondition 2 loadTimeFunction 1 dofs 1 1 values 1 0 set {}\n\
             BoundaryCondition 3 loadTimeFunction 1 dofs 1 2 values 1 0 set {}\n",
                set("x0"),
                set("y0")
            ),
        )
    } else {
        (
            "2dPlaneStress",
            format!(
                "BoundaryCondition 2 loadTimeFunction 1 dofs 1 1 values 1 0 set {}\n\
             BoundaryCondition 3 loadTimeFunction 1 dofs 1 1 values 1 0 set {}\n",
                set("x0"),
                set("x0")
            ),
        )
    };
    format!(
        "patch.out\nGmsh patch test\nLinearStatic nsteps 1\ndomain {domain}\nOutputManager\n\
         ndofman {} nelem {} ncrosssect 1 nmat 1 nbc 4 nic 0 nltf 1 nset {nset}\n\
         {mesh}\n\
         SimpleCS 1 thick 1 material 1 set {}\n\
         IsoLE 1 d 0 E 1 n {NU} tAlpha 0\n\
         BoundaryCondition 1 loadTimeFunction 1 dofs 1 {dim} values 1 0 set {}\n{lateral}\
         BoundaryCondition 4 loadTimeFunction 1 dofs 1 {dim} values 1 {STRAIN} set {}\n\
         ConstantFunction 1 f(t) 1\n",
        c.coords.len(),
        c.elements.len(),
        set("body"),
        set("bottom"),
        set("top"),
    )
}

#[test]
fn every_mapped_element_type_passes_the_patch_test() {
    for (file, etype, n) in [
        ("cube_hex.msh", "LSpace", 8),
        ("cube_tet.msh", "LTRSpace", 100),
        ("cube_tet10.msh", "QTRSpace", 100),
        ("cube_hex20.msh", "QSpace", 8),
        ("cube_prism.msh", "LWedge", 28),
        ("square_tri.msh", "TrPlaneStress2d", 26),
        ("square_quad.msh", "PlaneStress2d", 21),
        ("square_quad8.msh", "QPlaneStress2d", 21),
        ("square_tri6.msh", "QTrPlStr", 26),
        ("square_tri.msh", "TrPlaneStrain", 26),
        ("square_quad.msh", "Quad1PlaneStrain", 21),
        ("square_quad8.msh", "QPlaneStrain", 21),
        ("square_tri6.msh", "QTrPlaneStrain", 26),
        // Axisymmetric (x the radius, x = 0 the axis): a solid cylinder in uniaxial stress,
        // u_r = −ν ε r as in plane stress.
        ("square_tri.msh", "Axisymm3d", 26),
        ("square_quad.msh", "L4Axisymm", 21),
        ("square_quad8.msh", "Q4Axisymm", 21),
    ] {
        let plane = match etype {
            e if e.contains("Strain") => Plane::Strain,
            e if e.contains("Axisymm") => Plane::Axisymmetric,
            _ => Plane::Stress,
        };
        let c = convert(&data(file), plane).unwrap();
        assert_eq!(c.elements.len(), n, "{file}");
        assert!(c.elements.iter().all(|(t, _)| t.name() == etype), "{file}");
        assert_eq!(c.n_flipped, 0, "{file}: Gmsh's own elements are positive");
        let err = patch_error(&data(file), plane);
        println!("{file}: {n} {etype}, patch test error {err:.2e}");
        assert!(err < 1e-12, "{file}: {err}");
    }
}

/// `@gmsh "mesh.msh" nlgeo` (and `hertz import --nlgeo`) writes `nlgeo 1` on every element:
/// the tetrahedral cube compressed by 1 % in large deformation takes the St. Venant–Kirchhoff
/// answer of uniaxial stress, lateral stretch √(1 − ν(λ₁² − 1)) (E₂ = −ν E₁), at every node
/// to round-off, 3e-5 from the small-strain −ν ε that the same mesh gives without `nlgeo`.
#[test]
fn gmsh_meshes_in_large_deformation() {
    let mesh = data("cube_tet.msh");
    let c = convert(&mesh, Plane::Stress).unwrap();
    let lateral = (1.0 - NU * ((1.0 + STRAIN).powi(2) - 1.0)).sqrt() - 1.0;
    for (directive, want) in [(" nlgeo", lateral), ("", -NU * STRAIN)] {
        let text = patch_input(&c, &format!("@gmsh \"{}\"{directive}", mesh.display())).replace(
            "LinearStatic nsteps 1",
            "NonLinearStatic nsteps 1 controlmode 1 rtolf 1e-12 manrmsteps 1 maxiter 20",
        );
        let model = common::model_from_text(&text).unwrap();
        assert!(model
            .elements
            .iter()
            .all(|e| e.nlgeo != directive.is_empty()));
        let mut worst = f64::NAN;
        run_analysis(&model, &common::quiet(), |r| {
            worst = 0.0;
            for (n, node) in model.nodes.iter().enumerate() {
                let u = r.displacement(n, 1).unwrap();
                worst = worst.max((u - want * node.coords[0]).abs());
            }
            Ok(())
        })
        .unwrap();
        assert!(worst < 1e-12, "{directive:?}: {worst:e}");
    }
    assert!((lateral + NU * STRAIN).abs() > 1e-5);
    // `hertz import --nlgeo` writes the same element records.
    let mut c = c;
    c.nlgeo = true;
    assert!(c
        .records()
        .iter()
        .any(|r| r.starts_with("LTRSpace 1 ") && r.ends_with(" nlgeo 1")));
}

/// Gmsh's second-order tetrahedra (type 11) and 20-node hexahedra (type 17) map to QTRSpace and
/// QSpace with their mid-edge nodes where OOFEM's order has them: pure bending (κ about y),
/// u = (κxz, −νκyz, −κ(x² + ν(z² − y²))/2), prescribed on the boundary of the unit cube is
/// reproduced at every interior node to round-off, which a mid-edge node on the wrong edge (a
/// curved element) would spoil.
#[test]
fn gmsh_quadratic_3d_elements_reproduce_pure_bending() {
    for (file, etype) in [("cube_tet10.msh", "QTRSpace"), ("cube_hex20.msh", "QSpace")] {
        bending_3d(file, etype);
    }
}

fn bending_3d(file: &str, etype: &str) {
    const KAPPA: f64 = 0.01;
    let c = convert(&data(file), Plane::Stress).unwrap();
    assert!(c.elements.iter().all(|(t, _)| t.name() == etype));
    let exact = |x: [f64; 3]| {
        vec![
            KAPPA * x[0] * x[2],
            -NU * KAPPA * x[1] * x[2],
            -0.5 * KAPPA * (x[0] * x[0] + NU * (x[2] * x[2] - x[1] * x[1])),
        ]
    };
    let (worst, interior) = boundary_field_error(&c, "3d", &exact);
    assert!(interior > 5, "{file}: {interior} interior nodes");
    assert!(worst < 1e-13, "{file}: interior error {worst:e}");
}

/// Prescribe the displacement field `exact` (one value per DOF: 2 in 2D, 3 in 3D) on every node
/// of the unit square's or cube's boundary of the mesh `c` and solve it (E = 1, ν = NU, in
/// `domain`): the largest error at the interior nodes, and how many there are.
fn boundary_field_error(
    c: &hertz::mesh::gmsh::Converted,
    domain: &str,
    exact: &dyn Fn([f64; 3]) -> Vec<f64>,
) -> (f64, usize) {
    let dim = exact([0.0; 3]).len();
    let on_boundary = |x: [f64; 3]| {
        x[..dim]
            .iter()
            .any(|&v| v.abs() < 1e-12 || (v - 1.0).abs() < 1e-12)
    };
    let boundary: Vec<usize> = (0..c.coords.len())
        .filter(|&n| on_boundary(c.coords[n]))
        .collect();
    let nset0 = c.sets.len();
    let mut records = c.records();
    let mut bcs = String::new();
    let ids: Vec<String> = (1..=dim).map(|d| d.to_string()).collect();
    for (k, &n) in boundary.iter().enumerate() {
        records.push(format!("Set {} nodes 1 {}", nset0 + k + 1, n + 1));
        let u: Vec<String> = exact(c.coords[n])
            .iter()
            .map(|v| format!("{v:e}"))
            .collect();
        bcs.push_str(&format!(
            "BoundaryCondition {} loadTimeFunction 1 dofs {dim} {} values {dim} {} set {}\n",
            k + 1,
            ids.join(" "),
            u.join(" "),
            nset0 + k + 1
        ));
    }
    let text = format!(
        "bending.out\nQuadratic patch test\nLinearStatic nsteps 1\ndomain {domain}\n\
         OutputManager\nndofman {} nelem {} ncrosssect 1 nmat 1 nbc {} nic 0 nltf 1 nset {}\n\
         {}\nSimpleCS 1 thick 1 material 1 set 1\nIsoLE 1 d 0 E 1 n {NU} tAlpha 0\n\
         {bcs}ConstantFunction 1 f(t) 1\n",
        c.coords.len(),
        c.elements.len(),
        boundary.len(),
        nset0 + boundary.len(),
        records.join("\n"),
    );
    let model = common::model_from_text(&text).unwrap();
    let (mut worst, mut interior) = (f64::NAN, 0);
    run_analysis(&model, &common::quiet(), |r| {
        worst = 0.0;
        for n in (0..c.coords.len()).filter(|&n| !on_boundary(c.coords[n])) {
            interior += 1;
            for (d, ud) in (1u8..).zip(exact(c.coords[n])) {
                worst = worst.max((r.displacement(n, d).unwrap() - ud).abs());
            }
        }
        Ok(())
    })
    .unwrap();
    (worst, interior)
}

/// The 6-node triangles are quadratically complete: pure bending, u = (κxy, −κ(x² + ν'y²)/2)
/// (ν' = ν in plane stress, ν/(1−ν) in plane strain), prescribed on the boundary of the unit
/// square is reproduced at every interior node to round-off. The linear triangle cannot; nor
/// can the 8-node serendipity quadrangle on Gmsh's recombined (non-parallelogram) quads, whose
/// mapping is not affine (a known property of serendipity elements, not checked here).
#[test]
fn quadratic_elements_reproduce_pure_bending() {
    const KAPPA: f64 = 0.01;
    let bending_error = |file: &str, plane: Plane| -> f64 {
        let c = convert(&data(file), plane).unwrap();
        let nu = if plane == Plane::Strain {
            NU / (1.0 - NU)
        } else {
            NU
        };
        let exact = |x: [f64; 3]| {
            vec![
                KAPPA * x[0] * x[1],
                -0.5 * KAPPA * (x[0] * x[0] + nu * x[1] * x[1]),
            ]
        };
        boundary_field_error(&c, "2dPlaneStress", &exact).0
    };
    for (file, plane) in [
        ("square_tri6.msh", Plane::Stress),
        ("square_tri6.msh", Plane::Strain),
    ] {
        let err = bending_error(file, plane);
        println!("{file} ({plane:?}): pure bending error {err:.2e}");
        assert!(err < 1e-15, "{file} {plane:?}: {err}");
    }
    // The contrast: linear triangles miss the quadratic field by a visible amount.
    let err = bending_error("square_tri.msh", Plane::Stress);
    println!("square_tri.msh: pure bending error {err:.2e}");
    assert!(err > 1e-5, "{err}");
}

/// Physical curves and surfaces become element boundaries with hertz's local numbers: the
/// boundary nodes of each set lie on its plane and the sets' edge lengths add up.
#[test]
fn physical_groups_become_sets_of_element_boundaries() {
    let c = convert(&data("cube_tet.msh"), Plane::Stress).unwrap();
    let names: Vec<&str> = c.sets.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["body", "x0", "y0", "bottom", "top"]);
    for (name, axis, value) in [
        ("x0", 0, 0.0),
        ("y0", 1, 0.0),
        ("bottom", 2, 0.0),
        ("top", 2, 1.0),
    ] {
        let s = c.sets.iter().find(|s| s.name == name).unwrap();
        let mut area = 0.0;
        for &(e, b) in &s.boundaries {
            let (etype, nodes) = &c.elements[e];
            let face = etype.shape().boundaries()[b - 1];
            let x: Vec<[f64; 3]> = face.iter().map(|&a| c.coords[nodes[a]]).collect();
            assert!(
                x.iter().all(|p| (p[axis] - value).abs() < 1e-12),
                "{name}: {x:?}"
            );
            let (u, v) = (sub(x[1], x[0]), sub(x[2], x[0]));
            area += 0.5 * norm(cross(u, v));
        }
        assert!((area - 1.0).abs() < 1e-12, "{name}: area {area}");
    }
    let square = convert(&data("square_quad8.msh"), Plane::Stress).unwrap();
    let top = square.sets.iter().find(|s| s.name == "top").unwrap();
    let length: f64 = top
        .boundaries
        .iter()
        .map(|&(e, b)| {
            let (etype, nodes) = &square.elements[e];
            let edge = etype.shape().boundaries()[b - 1];
            // Quadratic edge: corners then the mid-side node, which lies half way.
            let x: Vec<[f64; 3]> = edge.iter().map(|&a| square.coords[nodes[a]]).collect();
            assert!((x[2][0] - 0.5 * (x[0][0] + x[1][0])).abs() < 1e-12);
            (x[1][0] - x[0][0]).abs()
        })
        .sum();
    assert!((length - 1.0).abs() < 1e-12, "top length {length}");
}

/// The sets `hertz import` and `@gmsh` write carry their physical groups' names (`name`), by
/// which the model finds them: "top" is the set of the faces at z = 1, "body" the elements.
#[test]
fn physical_group_names_name_the_sets() {
    let c = convert(&data("cube_tet.msh"), Plane::Stress).unwrap();
    let records = c.records().join("\n");
    let mesh = data("cube_tet.msh");
    for text in [
        patch_input(&c, &records),
        patch_input(&c, &format!("@gmsh \"{}\"", mesh.display())),
    ] {
        let model = crate::common::model_from_text(&text).unwrap();
        let top = model.set_named("top").unwrap();
        assert_eq!(top, c.sets.iter().find(|s| s.name == "top").unwrap().number);
        let nodes = &model.sets[top - 1].nodes;
        assert!(!nodes.is_empty());
        assert!(nodes.iter().all(|&n| model.nodes[n].coords[2] == 1.0));
        let body = model.set_named("body").unwrap();
        assert_eq!(model.sets[body - 1].elements.len(), model.elements.len());
        assert_eq!(model.set_named("Top"), None);
    }
}

/// Elements listed clockwise (a surface meshed with its normal along -z) are mirrored to a
/// positive Jacobian, and the model still passes the patch test.
#[test]
fn clockwise_elements_are_mirrored_and_still_exact() {
    let text = std::fs::read_to_string(data("square_quad.msh")).unwrap();
    let mut out = String::new();
    let mut in_elements = false;
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if line == "$Elements" || line == "$EndElements" {
            in_elements = line == "$Elements";
        } else if in_elements && words.len() == 3 + 2 + 4 && words[1] == "3" {
            // 2.2 record: tag, type 3 (quad), 2 tags, four nodes: reverse the nodes.
            let mut w = words.clone();
            w[5..9].reverse();
            out += &w.join(" ");
            out.push('\n');
            continue;
        }
        out += line;
        out.push('\n');
    }
    let mirrored = std::env::temp_dir().join(format!("hertz-cw-{}.msh", std::process::id()));
    std::fs::write(&mirrored, out).unwrap();
    let c = convert(&mirrored, Plane::Stress).unwrap();
    assert_eq!(c.n_flipped, c.elements.len());
    let err = patch_error(&mirrored, Plane::Stress);
    std::fs::remove_file(&mirrored).ok();
    assert!(err < 1e-12, "{err}");
}

/// `hertz import` writes the records `@gmsh` splices in: the fragment, @included, gives the same
/// model; and the 2.2 and 4.1 files of one mesh give the same records.
#[test]
fn import_fragment_equals_the_gmsh_record_and_formats_agree() {
    let dir = std::env::temp_dir().join(format!("hertz-import-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fragment = dir.join("hex.in");
    let status = std::process::Command::new(env!("CARGO_BIN_EXE_hertz"))
        .args(["import", data("cube_hex.msh").to_str().unwrap(), "-o"])
        .arg(&fragment)
        .output()
        .unwrap();
    assert!(status.status.success());
    let stderr = String::from_utf8_lossy(&status.stderr);
    assert!(stderr.contains("ndofman 27 nelem 8 nset 5"), "{stderr}");
    let c = convert(&data("cube_hex.msh"), Plane::Stress).unwrap();
    let written = std::fs::read_to_string(&fragment).unwrap();
    let records: Vec<&str> = written.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(records, c.records());
    std::fs::remove_dir_all(&dir).ok();

    // One mesh written by Gmsh in both formats converts to the same records.
    let v41 = convert(&data("square_tri.msh"), Plane::Stress).unwrap();
    let v22 = convert(&data("square_tri_v22.msh"), Plane::Stress).unwrap();
    assert!(v41.elements.len() == 26 && v41.sets.len() == 4);
    assert_eq!(v41.records(), v22.records());
}

/// The Hertz example meshed in Gmsh, in linear and in 6-node triangles: p0 and a within 2 % of
/// the closed form, in a handful of iterations.
#[test]
fn hertz_example_meshed_in_gmsh_meets_hertz() {
    for file in ["hertz_gmsh.in", "hertz_gmsh_tri6.in"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("examples/gmsh")
            .join(file);
        let (model, states, residuals) = common::solve_contact(&path);
        let iterations = residuals.len() - 1;
        let c = hertz::analytic::compare_hertz(&model, &states, 0.0).unwrap();
        println!(
            "{file}: F {:.4} p0 {:.4} vs {:.4} ({:+.2} %), a {:.4} vs {:.4} ({:+.2} %), {iterations} iterations",
            c.force,
            c.p0,
            c.p0_ref,
            100.0 * c.p0_error(),
            c.a,
            c.a_ref,
            100.0 * c.a_error()
        );
        assert!(
            c.p0_error().abs() < 0.02 && c.a_error().abs() < 0.02,
            "{file}"
        );
        assert!(iterations <= 5, "{file}: {iterations} iterations");
    }
}

/// The 3D tutorial example: an elastic sphere meshed in Gmsh with 10-node tetrahedra
/// (`-order 2`), its spherical surface's corner and mid-side nodes pressed onto a rigid plane by
/// node-to-face multipliers: p0 (the node on the axis) within 1 % and a within 2 % of Hertz for
/// the computed force, in a handful of iterations.
#[test]
fn sphere_meshed_in_gmsh_with_quadratic_tetrahedra_meets_hertz() {
    use hertz::analytic::{compare_hertz_sphere, contact_modulus};
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/gmsh/sphere_tet10.in");
    let (model, states, residuals) = common::solve_contact(&path);
    let iterations = residuals.len() - 1;
    let c = compare_hertz_sphere(
        &model,
        &states,
        10.0,
        contact_modulus(1000.0, 0.3, f64::INFINITY, 0.0),
    )
    .expect("a contact zone");
    println!(
        "F {:.4}, p0 {:+.2} %, a {:+.2} %, {iterations} iterations",
        c.force,
        100.0 * c.p0_error(),
        100.0 * c.a_error()
    );
    assert!(c.p0_error().abs() < 0.01 && c.a_error().abs() < 0.02);
    assert!(iterations <= 5, "{iterations} iterations");
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// A mesh hertz cannot represent is refused with what to do instead, naming the file.
#[test]
fn unsupported_element_types_and_binary_files_are_named() {
    let dir = std::env::temp_dir().join(format!("hertz-gmsh-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let quad9 = dir.join("quad9.msh");
    std::fs::write(
        &quad9,
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n9\n1 0 0 0\n2 1 0 0\n3 1 1 0\n\
         4 0 1 0\n5 0.5 0 0\n6 1 0.5 0\n7 0.5 1 0\n8 0 0.5 0\n9 0.5 0.5 0\n$EndNodes\n\
         $Elements\n1\n1 10 2 1 1 1 2 3 4 5 6 7 8 9\n$EndElements\n",
    )
    .unwrap();
    let e = convert(&quad9, Plane::Stress).unwrap_err().to_string();
    assert!(
        e.contains("quad9.msh") && e.contains("hertz has no 9-node quadrangle"),
        "{e}"
    );
    let binary = dir.join("binary.msh");
    std::fs::write(&binary, "$MeshFormat\n4.1 1 8\n").unwrap();
    let e = convert(&binary, Plane::Stress).unwrap_err().to_string();
    assert!(e.contains("binary .msh files are not read"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// Whatever the orientation of the input's elements, the .vtu cells are in VTK's order with a
/// positive volume: every other element of the hexahedron, tetrahedron and prism cubes is
/// written mirrored into the input, and each cell's VTK orientation is checked in the file.
#[test]
fn vtu_cells_are_positive_whatever_the_input_orientation() {
    let dir = std::env::temp_dir().join(format!("hertz-vtu-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for file in [
        "cube_hex.msh",
        "cube_tet.msh",
        "cube_tet10.msh",
        "cube_hex20.msh",
        "cube_prism.msh",
    ] {
        let mut c = convert(&data(file), Plane::Stress).unwrap();
        for (etype, nodes) in c.elements.iter_mut().step_by(2) {
            *nodes = etype.shape().mirror().iter().map(|&a| nodes[a]).collect();
        }
        let input = dir.join("cube.in");
        std::fs::write(&input, patch_input(&c, &c.records().join("\n"))).unwrap();
        for vtu_format in [VtuFormat::Ascii, VtuFormat::Binary] {
            let vtu = common::run_writing_vtu(&input, None, vtu_format);
            let arrays = common::read_vtu(&vtu);
            let block = |name: &str| arrays[name].clone();
            let (points, conn, types) =
                (block("coordinates"), block("connectivity"), block("types"));
            let p = |k: f64| {
                let k = k as usize;
                [points[3 * k], points[3 * k + 1], points[3 * k + 2]]
            };
            let mut at = 0;
            for &t in &types {
                let (n, sign) = match t as u8 {
                    12 => (8, 1.0),  // hexahedron: (p1-p0) x (p3-p0) . (p4-p0) > 0
                    10 => (4, 1.0),  // tetrahedron: (p1-p0) x (p2-p0) . (p3-p0) > 0
                    24 => (10, 1.0), // quadratic tetrahedron: corners as the tetrahedron's
                    25 => (20, 1.0), // quadratic hexahedron: corners as the hexahedron's
                    13 => (6, -1.0), // wedge: the base (0,1,2) faces away from (3,4,5)
                    other => panic!("cell type {other}"),
                };
                let q: Vec<[f64; 3]> = conn[at..at + n].iter().map(|&k| p(k)).collect();
                let (a, b, d) = match n {
                    8 | 20 => (sub(q[1], q[0]), sub(q[3], q[0]), sub(q[4], q[0])),
                    _ => (sub(q[1], q[0]), sub(q[2], q[0]), sub(q[3], q[0])),
                };
                let triple = dot(cross(a, b), d);
                assert!(
                    sign * triple > 0.0,
                    "{file} ({vtu_format:?}): cell at {at} has triple product {triple}"
                );
                // VTK's quadratic cells: their mid-edge nodes at the middle of VTK's edges.
                let edges: &[(usize, usize)] = match n {
                    10 => &[(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)],
                    20 => &[
                        (0, 1),
                        (1, 2),
                        (2, 3),
                        (3, 0),
                        (4, 5),
                        (5, 6),
                        (6, 7),
                        (7, 4),
                        (0, 4),
                        (1, 5),
                        (2, 6),
                        (3, 7),
                    ],
                    _ => &[],
                };
                let first = if n == 10 { 4 } else { 8 };
                for (k, &(i, j)) in edges.iter().enumerate() {
                    let m = [0, 1, 2].map(|c| 0.5 * (q[i][c] + q[j][c]));
                    assert!(
                        (0..3).all(|c| (q[first + k][c] - m[c]).abs() < 1e-12),
                        "{file}: cell at {at}, mid-edge node {}",
                        first + k
                    );
                }
                at += n;
            }
            assert_eq!(at, conn.len());
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `tests/data/gmsh/square_tri_v22.msh` rewritten by `edit` (line by line, with the section it is
/// in) into a temporary file.
fn edited_square(tag: &str, edit: impl Fn(&str, &str) -> Option<String>) -> PathBuf {
    let text = std::fs::read_to_string(data("square_tri_v22.msh")).unwrap();
    let mut section = String::new();
    let mut out = String::new();
    for line in text.lines() {
        if line.starts_with('$') {
            section = line.to_string();
        }
        if let Some(l) = edit(&section, line) {
            out += &l;
            out.push('\n');
        }
    }
    let path = std::env::temp_dir().join(format!("hertz-{tag}-{}.msh", std::process::id()));
    std::fs::write(&path, out).unwrap();
    path
}

/// A mesh without physical groups gives no sets: the error says so instead of only that a set
/// record is missing; a NaN coordinate is an error at its line, naming it.
#[test]
fn gmsh_mistakes_are_named() {
    // No physical groups: drop $PhysicalNames, set every element's physical tag to 0.
    let groupless = edited_square("groupless", |section, line| {
        if section.starts_with("$PhysicalNames") || section == "$EndPhysicalNames" {
            return None;
        }
        let w: Vec<&str> = line.split_whitespace().collect();
        if section == "$Elements" && w.len() > 4 {
            let mut w: Vec<String> = w.iter().map(|s| s.to_string()).collect();
            w[3] = "0".into();
            return Some(w.join(" "));
        }
        Some(line.to_string())
    });
    let c = convert(&groupless, Plane::Stress).unwrap();
    assert!(c.sets.is_empty());
    let text = patch_input(
        &convert(&data("square_tri_v22.msh"), Plane::Stress).unwrap(),
        &format!("@gmsh \"{}\"", groupless.display()),
    );
    let err = common::model_from_text(&text).unwrap_err().to_string();
    assert!(err.contains("expected set record 1 of"), "{err}");
    assert!(
        err.contains("has no physical groups, so `@gmsh` gives no sets"),
        "{err}"
    );
    std::fs::remove_file(&groupless).ok();

    // A NaN coordinate: node 5 (line 17 of the file).
    let nan = edited_square("nan", |section, line| {
        Some(if section == "$Nodes" && line.starts_with("5 ") {
            "5 nan 0 0".to_string()
        } else {
            line.to_string()
        })
    });
    let err = convert(&nan, Plane::Stress).unwrap_err().to_string();
    assert!(
        err.contains(":17: node coordinate x is `NaN`, not a finite number"),
        "{err}"
    );
    std::fs::remove_file(&nan).ok();
}

/// A mesh of 6-node triangles asked for as axisymmetric is refused with what to mesh instead
/// (OOFEM has no 6-node axisymmetric triangle).
#[test]
fn quadratic_triangles_have_no_axisymmetric_element() {
    let err = convert(&data("square_tri6.msh"), Plane::Axisymmetric)
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("6-node triangles have no axisymmetric element"),
        "{err}"
    );
}
