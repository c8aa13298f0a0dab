//! `hertz plot` on a real run (the Hertz example meshed in Gmsh): each chart is written and holds
//! its series — one marker per contact node with a pressure, the Hertz curve's 401 points, one
//! residual line per step with a point per iteration, the reaction over the prescribed value.

use std::path::Path;
use std::process::Command;

fn hertz(args: &[&str]) -> std::process::Output {
    let out = Command::new(env!("CARGO_BIN_EXE_hertz"))
        .args(args)
        .output()
        .expect("run hertz");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// Point counts of the polylines drawn in `color` (plotters writes `stroke="#RRGGBB"`).
fn polylines(svg: &str, color: &str) -> Vec<usize> {
    svg.split("<polyline")
        .skip(1)
        .filter(|p| p.contains(&format!("stroke=\"{color}\"")))
        .map(|p| {
            let pts = p.split("points=\"").nth(1).unwrap();
            pts[..pts.find('"').unwrap()].split_whitespace().count()
        })
        .collect()
}

#[test]
fn plots_hold_the_runs_series() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("hertz-plot-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let d = dir.to_str().unwrap();
    let input = root.join("examples/gmsh/hertz_gmsh.in");
    hertz(&["run", "-q", input.to_str().unwrap(), "-o", d]);
    let csv = dir.join("hertz_gmsh.contact.csv");
    hertz(&["plot", csv.to_str().unwrap(), "--hertz", "25.75,0.4686"]);

    // Pressure: a marker per contact node with a finite pressure, and the closed form.
    let rows = std::fs::read_to_string(&csv).unwrap();
    let with_pressure = rows
        .lines()
        .skip(1)
        .filter(|l| {
            l.split(',')
                .nth(8)
                .unwrap()
                .parse::<f64>()
                .unwrap()
                .is_finite()
        })
        .count();
    let svg = std::fs::read_to_string(dir.join("hertz_gmsh.pressure.svg")).unwrap();
    assert!(with_pressure > 30);
    // One marker per node, and the legend's.
    assert_eq!(svg.matches("<circle").count(), with_pressure + 1);
    assert!(polylines(&svg, "#D62728").contains(&401), "Hertz curve");
    assert!(svg.contains("Hertz: p0 = 25.75, a = 0.4686"));

    // Residuals: one step, its iterations 0..n.
    let newton = std::fs::read_to_string(dir.join("hertz_gmsh.newton.csv")).unwrap();
    let n_residuals = newton.lines().count() - 1;
    let svg = std::fs::read_to_string(dir.join("hertz_gmsh.residuals.svg")).unwrap();
    assert!(
        polylines(&svg, "#1F77B4").contains(&n_residuals),
        "{n_residuals}"
    );

    // Load: the driven bottom (bc 2, DOF 2) from the origin to its one step.
    let svg = std::fs::read_to_string(dir.join("hertz_gmsh.load.svg")).unwrap();
    assert!(polylines(&svg, "#1F77B4").contains(&2));
    assert!(svg.contains("bc2, DOF 2"));

    // Load over time: a file of its own beside the load chart, not over it.
    hertz(&[
        "plot",
        dir.join("hertz_gmsh").to_str().unwrap(),
        "-c",
        "load",
        "--time",
    ]);
    let over_time = std::fs::read_to_string(dir.join("hertz_gmsh.load_time.svg")).unwrap();
    assert!(over_time.contains(">\ntime\n</text>"), "the time axis");
    assert_eq!(
        std::fs::read_to_string(dir.join("hertz_gmsh.load.svg")).unwrap(),
        svg
    );

    // PNG: a real image of the chart's size.
    hertz(&[
        "plot",
        dir.join("hertz_gmsh").to_str().unwrap(),
        "--png",
        "-c",
        "residuals",
    ]);
    let png = std::fs::read(dir.join("hertz_gmsh.residuals.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 900);
    std::fs::remove_dir_all(&dir).ok();
}
