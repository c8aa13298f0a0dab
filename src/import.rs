//! `hertz import`: a Gmsh mesh into node, element and set records to `@include`.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use hertz::mesh::gmsh::Plane;
use hertz::output::vtu::VtuFormat;
use std::path::PathBuf;

/// `hertz import`: arguments.
#[derive(Debug, clap::Args)]
pub struct ImportArgs {
    /// Gmsh mesh (.msh 2.2 or 4.1, ASCII)
    pub mesh: PathBuf,
    /// Output file (default: MESH with the extension .in, e.g. disk.msh -> disk.in); an existing
    /// file is overwritten only if `hertz import` wrote it
    #[arg(short, long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// 2D element types: plane stress, plane strain or axisymmetric
    #[arg(long, default_value = "stress", value_parser = plane_parser())]
    pub plane: Plane,
    /// Large deformation: `nlgeo 1` on every element record
    #[arg(long)]
    pub nlgeo: bool,
}

/// `hertz import MESH [-o FILE] [--plane stress|strain|axisymmetric] [--nlgeo]`: write the records; returns
/// what to tell the user (the file, the counts, the sets, and a warning line if the mesh has no
/// groups).
pub fn run(args: &ImportArgs) -> hertz::error::Result<Vec<String>> {
    let mut c = hertz::mesh::gmsh::convert(&args.mesh, args.plane)?;
    c.nlgeo = args.nlgeo;
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| args.mesh.with_extension("in"));
    c.write_fragment(&out, &args.mesh)?;
    let mut lines = vec![format!(
        "wrote {}: {} nodes, {} elements ({}D); counts record: {}",
        out.display(),
        c.coords.len(),
        c.elements.len(),
        c.dim,
        c.counts()
    )];
    lines.extend(c.set_summary().into_iter().map(|l| format!("  {l}")));
    if c.sets.is_empty() {
        lines.push(format!(
            "warning: {} has no physical groups, so the records have no sets (nset 0): hertz \
             makes one set per physical group; define Physical groups in Gmsh for the body and \
             each loaded, supported or contact boundary",
            args.mesh.display()
        ));
    }
    Ok(lines)
}

/// `--plane`'s values.
fn plane_parser() -> impl TypedValueParser<Value = Plane> {
    PossibleValuesParser::new([
        PossibleValue::new("stress")
            .help("PlaneStress2d, TrPlaneStress2d, QPlaneStress2d, QTrPlStr"),
        PossibleValue::new("strain")
            .help("Quad1PlaneStrain, TrPlaneStrain, QPlaneStrain, QTrPlaneStrain"),
        PossibleValue::new("axisymmetric")
            .help("L4Axisymm, Axisymm3d, Q4Axisymm: x is the radius, per radian"),
    ])
    .map(|s| match s.as_str() {
        "strain" => Plane::Strain,
        "axisymmetric" => Plane::Axisymmetric,
        _ => Plane::Stress,
    })
}

/// `--vtu`'s values.
pub fn vtu_parser() -> impl TypedValueParser<Value = VtuFormat> {
    PossibleValuesParser::new([
        PossibleValue::new("ascii")
            .help("Numbers as text (shortest digits that read back to the same doubles)"),
        PossibleValue::new("binary").help(
            "Raw little-endian bytes appended after the XML (`AppendedData encoding=\"raw\"`): \
             smaller, exact and several times faster to write and to read",
        ),
    ])
    .map(|s| match s.as_str() {
        "binary" => VtuFormat::Binary,
        _ => VtuFormat::Ascii,
    })
}
