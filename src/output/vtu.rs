//! ParaView output: one `.vtu` (unstructured grid, ASCII) per step and a `.pvd` collection.
//! Point data: displacement, reaction; cell data: strain and stress averaged over the element's
//! integration points (full Voigt order xx, yy, zz, yz, xz, xy).

use super::write_atomic;
use crate::error::Result;
use crate::fem::geometry::det_j_at_centre;
use crate::fem::Shape;
use crate::model::Model;
use crate::solve::StepResult;
use std::fmt::Write;
use std::path::Path;

/// VTK cell type and the permutation from OOFEM to VTK node order.
fn vtk_cell(shape: Shape) -> (u8, &'static [usize]) {
    match shape {
        Shape::Line2 => (3, &[0, 1]),
        Shape::Line3 => (21, &[0, 1, 2]),
        Shape::Tri3 => (5, &[0, 1, 2]),
        Shape::Quad4 => (9, &[0, 1, 2, 3]),
        Shape::Quad8 => (23, &[0, 1, 2, 3, 4, 5, 6, 7]),
        Shape::Tet4 => (10, &[0, 2, 1, 3]),
        Shape::Hexa8 => (12, &[0, 1, 2, 3, 4, 5, 6, 7]),
        Shape::Wedge6 => (13, &[0, 2, 1, 3, 5, 4]),
    }
}

fn data_array(s: &mut String, name: &str, ncomp: usize, values: impl Iterator<Item = f64>) {
    use rayon::prelude::*;
    let _ = writeln!(s, "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"{ncomp}\" format=\"ascii\">");
    let values: Vec<f64> = values.collect();
    // Formatting is most of the time of writing a large file: chunks of whole tuples in parallel.
    let chunk = 4096 * ncomp;
    let parts: Vec<String> = values
        .par_chunks(chunk)
        .map(|c| {
            let mut s = String::with_capacity(24 * c.len());
            for (i, v) in c.iter().enumerate() {
                let _ = write!(s, "{v:e}");
                s.push(if (i + 1) % ncomp == 0 { '\n' } else { ' ' });
            }
            s
        })
        .collect();
    for p in parts {
        s.push_str(&p);
    }
    s.push_str("</DataArray>\n");
}

/// Write `<dir>/<stem>.<step>.vtu`; returns its file name.
pub fn write_step(model: &Model, res: &StepResult, dir: &Path, stem: &str) -> Result<String> {
    let nn = model.nodes.len();
    let ne = model.elements.len();
    let mut s = String::with_capacity(64 * (nn + ne));
    s.push_str("<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n");
    let _ = writeln!(s, "<Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{ne}\">");
    s.push_str("<Points>\n");
    data_array(
        &mut s,
        "coordinates",
        3,
        model.nodes.iter().flat_map(|n| n.coords),
    );
    s.push_str(
        "</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n",
    );
    let mut offsets = Vec::with_capacity(ne);
    let mut types = Vec::with_capacity(ne);
    let mut off = 0;
    for el in &model.elements {
        let shape = el.etype.shape();
        let (t, perm) = vtk_cell(shape);
        // VTK's orders are for positively oriented elements; a mirrored input element (hertz
        // takes either orientation) is written mirrored back, so no cell has a negative volume.
        let x: Vec<[f64; 3]> = el.nodes.iter().map(|&n| model.nodes[n].coords).collect();
        let flip = det_j_at_centre(shape, &x) < 0.0;
        for &k in perm {
            let k = if flip { shape.mirror()[k] } else { k };
            let _ = write!(s, "{} ", el.nodes[k]);
        }
        s.push('\n');
        off += perm.len();
        offsets.push(off);
        types.push(t);
    }
    s.push_str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for o in offsets {
        let _ = write!(s, "{o} ");
    }
    s.push_str("\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for t in types {
        let _ = write!(s, "{t} ");
    }
    s.push_str("\n</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\">\n");
    let disp = (0..nn)
        .flat_map(|n| (1..=3u8).map(move |d| (n, d)))
        .map(|(n, d)| res.displacement(n, d).unwrap_or(0.0));
    data_array(&mut s, "displacement", 3, disp);
    let mut reac = vec![0.0; 3 * nn];
    for (&(n, d, _), &r) in res.dofs.prescribed.iter().zip(res.reactions) {
        reac[3 * n + d as usize - 1] = r;
    }
    data_array(&mut s, "reaction", 3, reac.into_iter());
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
        data_array(&mut s, "contact_gap", 1, gap.into_iter());
        data_array(&mut s, "contact_force", 1, force.into_iter());
        data_array(&mut s, "contact_pressure", 1, pressure.into_iter());
        data_array(&mut s, "contact_active", 1, active.into_iter());
    }
    s.push_str("</PointData>\n<CellData>\n");
    for (name, pick) in [("strain", 0), ("stress", 1)] {
        let vals = res.states.iter().flat_map(|st| {
            let mut avg = [0.0; 6];
            for g in st {
                let v = if pick == 0 { g.strain } else { g.stress };
                for i in 0..6 {
                    avg[i] += v[i] / st.len().max(1) as f64;
                }
            }
            avg
        });
        data_array(&mut s, name, 6, vals);
    }
    s.push_str("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    let name = format!("{stem}.{}.vtu", res.step);
    write_atomic(&dir.join(&name), s.as_bytes())?;
    Ok(name)
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
