//! `hertz import`'s arguments, for [`hertz::mesh::gmsh::import_command`].

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use hertz::mesh::gmsh::{ImportOptions, Plane};
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
    /// 2D element types: plane stress or plane strain
    #[arg(long, default_value = "stress", value_parser = plane_parser())]
    pub plane: Plane,
    /// Large deformation: `nlgeo 1` on every element record
    #[arg(long)]
    pub nlgeo: bool,
}

impl ImportArgs {
    pub fn options(&self) -> ImportOptions {
        ImportOptions {
            mesh: self.mesh.clone(),
            output: self.output.clone(),
            plane: self.plane,
            nlgeo: self.nlgeo,
        }
    }
}

/// `--plane`'s values.
fn plane_parser() -> impl TypedValueParser<Value = Plane> {
    PossibleValuesParser::new([
        PossibleValue::new("stress")
            .help("PlaneStress2d, TrPlaneStress2d, QPlaneStress2d, QTrPlStr"),
        PossibleValue::new("strain")
            .help("Quad1PlaneStrain, TrPlaneStrain, QPlaneStrain, QTrPlaneStrain"),
    ])
    .map(|s| match s.as_str() {
        "strain" => Plane::Strain,
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
