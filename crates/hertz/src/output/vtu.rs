//! ParaView output: one `.vtu` (unstructured grid, ASCII or raw appended binary) per step and
//! a `.pvd` collection.
//! Point data: displacement (and in dynamics velocity, acceleration), reaction; cell data: strain and stress (with plastic materials the
//! plastic strain, κ and damage) averaged over the element's
//! integration points (full Voigt order xx, yy, zz, yz, xz, xy).

use super::{write_atomic, write_atomic_parts};
use crate::error::Result;
use crate::fem::geometry::det_j_at_centre;
use crate::fem::Shape;
use crate::material::plasticity::PlasticState;
use crate::model::Model;
use crate::solid::GpState;
use crate::solve::StepResult;
use std::fmt::Write;
use std::path::Path;

/// VTK cell type and the permutation from OOFEM to VTK node order.
fn vtk_cell(shape: Shape) -> (u8, &'static [usize]) {
    match shape {
        Shape::Line2 => (3, &[0, 1]),
        Shape::Line3 => (21, &[0, 1, 2]),
        Shape::Tri3 => (5, &[0, 1, 2]),
        Shape::Tri6 => (22, &[0, 1, 2, 3, 4, 5]),
        Shape::Quad4 => (9, &[0, 1, 2, 3]),
        Shape::Quad8 => (23, &[0, 1, 2, 3, 4, 5, 6, 7]),
        Shape::Tet4 => (10, &[0, 2, 1, 3]),
        // VTK_QUADRATIC_TETRA: VTK's corners are OOFEM's 1, 3, 2, 4, its edges (0,1), (1,2),
        // (2,0), (0,3), (1,3), (2,3) of those.
        Shape::Tet10 => (24, &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8]),
        Shape::Hexa8 => (12, &[0, 1, 2, 3, 4, 5, 6, 7]),
        // VTK_QUADRATIC_HEXAHEDRON: corners as the hexahedron's, then its edges in Hexa20's
        // order (the two faces' edges, then the four joining them).
        Shape::Hexa20 => (
            25,
            &[
                0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
            ],
        ),
        Shape::Wedge6 => (13, &[0, 2, 1, 3, 5, 4]),
    }
}

/// How the `.vtu` arrays are stored.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum VtuFormat {
    /// Numbers as text (shortest digits that read back to the same doubles).
    #[default]
    Ascii,
    /// Raw little-endian bytes appended after the XML (`AppendedData encoding="raw"`):
    /// smaller, exact and several times faster to write and to read.
    Binary,
}

/// The XML of one `.vtu` and, for [`VtuFormat::Binary`], its appended data block.
struct VtuWriter {
    format: VtuFormat,
    xml: String,
    appended: Vec<u8>,
}

/// A value type of a VTK data array.
trait VtkValue: Copy + Send + Sync {
    const NAME: &'static str;
    fn push_text(self, s: &mut String);
    fn push_bytes(self, b: &mut Vec<u8>);
}

impl VtkValue for f64 {
    const NAME: &'static str = "Float64";
    fn push_text(self, s: &mut String) {
        if self.is_finite() {
            s.push_str(ryu::Buffer::new().format_finite(self));
        } else {
            let _ = write!(s, "{self}");
        }
    }
    fn push_bytes(self, b: &mut Vec<u8>) {
        b.extend_from_slice(&self.to_le_bytes());
    }
}

impl VtkValue for i64 {
    const NAME: &'static str = "Int64";
    fn push_text(self, s: &mut String) {
        let _ = write!(s, "{self}");
    }
    fn push_bytes(self, b: &mut Vec<u8>) {
        b.extend_from_slice(&self.to_le_bytes());
    }
}

impl VtkValue for u8 {
    const NAME: &'static str = "UInt8";
    fn push_text(self, s: &mut String) {
        let _ = write!(s, "{self}");
    }
    fn push_bytes(self, b: &mut Vec<u8>) {
        b.push(self);
    }
}

impl VtuWriter {
    fn new(format: VtuFormat, capacity: usize) -> Self {
        let mut xml = String::with_capacity(match format {
            VtuFormat::Ascii => capacity,
            VtuFormat::Binary => 4096,
        });
        let _ = writeln!(xml, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n<UnstructuredGrid>");
        VtuWriter {
            format,
            xml,
            appended: Vec::with_capacity(match format {
                VtuFormat::Ascii => 0,
                VtuFormat::Binary => capacity / 2,
            }),
        }
    }

    /// One data array of `ncomp`-component tuples.
    fn array<T: VtkValue>(&mut self, name: &str, ncomp: usize, values: &[T]) {
        use rayon::prelude::*;
        let _ = write!(
            self.xml,
            "<DataArray type=\"{}\" Name=\"{name}\" NumberOfComponents=\"{ncomp}\" ",
            T::NAME
        );
        match self.format {
            VtuFormat::Ascii => {
                self.xml.push_str("format=\"ascii\">\n");
                // Formatting is most of the time of writing a large file: chunks of whole
                // tuples in parallel, a tuple per line.
                let parts: Vec<String> = values
                    .par_chunks(4096 * ncomp)
                    .map(|c| {
                        let mut s = String::with_capacity(24 * c.len());
                        for (i, &v) in c.iter().enumerate() {
                            v.push_text(&mut s);
                            s.push(if (i + 1) % ncomp == 0 { '\n' } else { ' ' });
                        }
                        s
                    })
                    .collect();
                for p in parts {
                    self.xml.push_str(&p);
                }
                self.xml.push_str("</DataArray>\n");
            }
            VtuFormat::Binary => {
                let _ = writeln!(
                    self.xml,
                    "format=\"appended\" offset=\"{}\"/>",
                    self.appended.len()
                );
                let bytes = std::mem::size_of_val(values);
                self.appended
                    .extend_from_slice(&(bytes as u64).to_le_bytes());
                for &v in values {
                    v.push_bytes(&mut self.appended);
                }
            }
        }
    }

    /// Close the document and write it whole to `path`.
    fn finish(mut self, path: &Path) -> Result<()> {
        self.xml.push_str("</UnstructuredGrid>\n");
        match self.format {
            VtuFormat::Ascii => {
                self.xml.push_str("</VTKFile>\n");
                write_atomic(path, self.xml.as_bytes())
            }
            VtuFormat::Binary => {
                self.xml.push_str("<AppendedData encoding=\"raw\">\n_");
                let tail = "\n</AppendedData>\n</VTKFile>\n";
                write_atomic_parts(
                    path,
                    &[self.xml.as_bytes(), &self.appended, tail.as_bytes()],
                )
            }
        }
    }
}

/// Write `<dir>/<stem>.<step>.vtu`; returns its file name.
pub fn write_step(
    model: &Model,
    res: &StepResult,
    dir: &Path,
    stem: &str,
    format: VtuFormat,
) -> Result<String> {
    let nn = model.nodes.len();
    let ne = model.elements.len();
    let mut w = VtuWriter::new(format, 64 * (nn + ne));
    let _ = writeln!(
        w.xml,
        "<Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{ne}\">\n<Points>"
    );
    let coords: Vec<f64> = model.nodes.iter().flat_map(|n| n.coords).collect();
    w.array("coordinates", 3, &coords);
    w.xml.push_str("</Points>\n<Cells>\n");
    let mut connectivity: Vec<i64> = Vec::new();
    let mut offsets: Vec<i64> = Vec::with_capacity(ne);
    let mut types: Vec<u8> = Vec::with_capacity(ne);
    for el in &model.elements {
        let shape = el.etype.shape();
        let (t, perm) = vtk_cell(shape);
        // VTK's orders are for positively oriented elements; a mirrored input element (hertz
        // takes either orientation) is written mirrored back, so no cell has a negative volume.
        let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| model.nodes[n].coords).collect();
        let flip = det_j_at_centre(shape, &x) < 0.0;
        for &k in perm {
            let k = if flip { shape.mirror()[k] } else { k };
            connectivity.push(el.nodes[k] as i64);
        }
        offsets.push(connectivity.len() as i64);
        types.push(t);
    }
    w.array("connectivity", 1, &connectivity);
    w.array("offsets", 1, &offsets);
    w.array("types", 1, &types);
    w.xml
        .push_str("</Cells>\n<PointData Vectors=\"displacement\">\n");
    let disp: Vec<f64> = (0..nn)
        .flat_map(|n| (1..=3u8).map(move |d| (n, d)))
        .map(|(n, d)| res.displacement(n, d).unwrap_or(0.0))
        .collect();
    w.array("displacement", 3, &disp);
    if let Some(m) = &res.motion {
        for (name, values) in [("velocity", m.velocity), ("acceleration", m.acceleration)] {
            let field: Vec<f64> = (0..nn)
                .flat_map(|n| (1..=3u8).map(move |d| (n, d)))
                .map(|(n, d)| {
                    res.dofs
                        .code(n, d)
                        .map_or(0.0, |c| res.dofs.value(values, c))
                })
                .collect();
            w.array(name, 3, &field);
        }
    }
    let mut reac = vec![0.0; 3 * nn];
    for (&(n, d, _), &r) in res.dofs.prescribed.iter().zip(res.reactions) {
        reac[3 * n + d as usize - 1] = r;
    }
    w.array("reaction", 3, &reac);
    if !res.contact.is_empty() {
        // Contact point data; NaN gap where a node takes no part in contact.
        let mut gap = vec![f64::NAN; nn];
        let mut force = vec![0.0; nn];
        let mut pressure = vec![0.0; nn];
        let mut active = vec![0.0; nn];
        for c in res.contact {
            gap[c.node] = c.gap;
            force[c.node] += c.force;
            pressure[c.node] += if c.pressure.is_finite() {
                c.pressure
            } else {
                0.0
            };
            active[c.node] = f64::from(u8::from(c.active)).max(active[c.node]);
        }
        if res.contact.iter().any(|c| c.friction.is_some()) {
            // Friction force (magnitude) and 1 where the node slides.
            let mut friction = vec![0.0; nn];
            let mut slip = vec![0.0; nn];
            for c in res.contact {
                if let Some((stick, f)) = c.friction {
                    friction[c.node] += f;
                    slip[c.node] = f64::from(u8::from(!stick)).max(slip[c.node]);
                }
            }
            w.array("contact_friction", 1, &friction);
            w.array("contact_slip", 1, &slip);
        }
        w.array("contact_gap", 1, &gap);
        w.array("contact_force", 1, &force);
        w.array("contact_pressure", 1, &pressure);
        w.array("contact_active", 1, &active);
    }
    w.xml.push_str("</PointData>\n<CellData>\n");
    let means = |f: fn(&GpState) -> [f64; 6]| -> Vec<f64> {
        (res.states.iter())
            .flat_map(|st| GpState::mean(st, f))
            .collect()
    };
    w.array("strain", 6, &means(|g| g.strain));
    w.array("stress", 6, &means(|g| g.stress));
    if res.states.iter().flatten().any(|g| g.plastic.is_some()) {
        plastic_cells(res, &mut w);
    }
    w.xml.push_str("</CellData>\n</Piece>\n");
    let name = format!("{stem}.{}.vtu", res.step);
    w.finish(&dir.join(&name))?;
    Ok(name)
}

/// Cell data of plastic materials (0 in the other elements): `plastic_strain` (6 components),
/// `equivalent_plastic_strain` κ and `damage`, averaged over the element's points, and the
/// largest κ of its points, `max_equivalent_plastic_strain`.
fn plastic_cells(res: &StepResult, w: &mut VtuWriter) {
    let averaged = |pick: &dyn Fn(&PlasticState) -> f64| -> Vec<f64> {
        res.states
            .iter()
            .map(|st| {
                let n = st.len().max(1) as f64;
                st.iter()
                    .filter_map(|g| g.plastic.as_ref())
                    .map(pick)
                    .sum::<f64>()
                    / n
            })
            .collect()
    };
    let strain: Vec<f64> = (0..6)
        .map(|i| averaged(&|p: &PlasticState| p.strain[i]))
        .collect::<Vec<_>>()
        .concat();
    // Component-major to cell-major.
    let cells = res.states.len();
    let strain: Vec<f64> = (0..cells)
        .flat_map(|c| (0..6).map(move |i| (c, i)))
        .map(|(c, i)| strain[i * cells + c])
        .collect();
    w.array("plastic_strain", 6, &strain);
    w.array(
        "equivalent_plastic_strain",
        1,
        &averaged(&|p: &PlasticState| p.kappa),
    );
    let max: Vec<f64> = res
        .states
        .iter()
        .map(|st| {
            st.iter()
                .filter_map(|g| g.plastic.map(|p| p.kappa))
                .fold(0.0, f64::max)
        })
        .collect();
    w.array("max_equivalent_plastic_strain", 1, &max);
    w.array("damage", 1, &averaged(&|p: &PlasticState| p.damage));
}

/// Write the `.pvd` collection of the step files written so far.
pub fn write_collection(dir: &Path, stem: &str, steps: &[(f64, String)]) -> Result<()> {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n",
    );
    for (t, f) in steps {
        let _ = writeln!(
            s,
            "<DataSet timestep=\"{t}\" group=\"\" part=\"0\" file=\"{f}\"/>"
        );
    }
    s.push_str("</Collection>\n</VTKFile>\n");
    write_atomic(&dir.join(format!("{stem}.pvd")), s.as_bytes())
}
