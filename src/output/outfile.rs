//! The OOFEM-style `.out` text file (spec §4): per step the DOF values of the selected nodes, the
//! integration-point strains and stresses (or F and P for `nlgeo 1`), and the reaction table.

use crate::assembly::DofMap;
use crate::model::{AnalysisKind, DofId, Model};
use crate::solve::StepResult;
use std::fmt::Write;

/// Header written once at the top.
pub fn header(model: &Model) -> String {
    format!(
        "\n############################################################## www.oofem.org ###\n\
         #### hertz {} (OOFEM-compatible output)\n\
         ##################################################################################\n\n\
         Starting analysis on: {}\n{}\n",
        env!("CARGO_PKG_VERSION"),
        timestamp(),
        model.description
    )
}

/// Footer written once at the end.
pub fn footer(total_seconds: f64) -> String {
    format!(
        "\nFinishing analysis on: {}\n\nReal time consumed: {:.3} [s]\n",
        timestamp(),
        total_seconds
    )
}

fn timestamp() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    format!("{secs} s since the Unix epoch")
}

/// The block of one step.
pub fn step_block(model: &Model, res: &StepResult) -> String {
    let mut s = String::new();
    match model.analysis.kind {
        AnalysisKind::NonLinearStatic => {
            let _ = write!(
                s,
                "\n\nOutput for time {:.3e}, solution step number {}\nReached load level : {:20.6} in {} iterations\n\n",
                res.time, res.step, 1.0, res.info.iterations
            );
        }
        _ => {
            let _ = write!(
                s,
                "\n==============================================================\nOutput for time {:.8e} \n\
                 ==============================================================\nOutput for domain   1\n",
                res.time
            );
        }
    }
    s.push_str("\n\nDofManager output:\n------------------\n");
    for (n, node) in model.nodes.iter().enumerate() {
        if !model.output.node(n + 1) {
            continue;
        }
        let class = if node.slave.is_some() {
            "SlaveNode"
        } else {
            "Node"
        };
        let _ = writeln!(s, "{:<8}{:8} ({:8}):", class, node.label, n + 1);
        for &(d, code) in &res.dofs.node_dofs[n] {
            let _ = writeln!(
                s,
                "  dof {}   d {}",
                d,
                sci_sign(res.dofs.value(res.u, code), 8)
            );
        }
    }
    s.push_str("\n\nElement output:\n---------------\n");
    for (e, el) in model.elements.iter().enumerate() {
        if !model.output.element(e + 1) {
            continue;
        }
        let _ = writeln!(s, "element {} ({:8}) :", el.label, e + 1);
        for (g, st) in res.states[e].iter().enumerate() {
            let _ = write!(s, "  GP {:2}.{:<2} :", 1, g + 1);
            if el.nlgeo {
                let order = [
                    (0, 0),
                    (1, 1),
                    (2, 2),
                    (1, 2),
                    (0, 2),
                    (0, 1),
                    (2, 1),
                    (2, 0),
                    (1, 0),
                ];
                s.push_str("  F ");
                for (i, j) in order {
                    let _ = write!(s, " {}", sci(st.f[i][j], 4));
                }
                s.push_str("\n  P");
                for (i, j) in order {
                    let _ = write!(s, " {}", sci(st.p[i][j], 4));
                }
            } else {
                s.push_str("  strains ");
                for v in st.strain {
                    let _ = write!(s, " {}", sci(v, 4));
                }
                s.push_str("\n              stresses");
                for v in st.stress {
                    let _ = write!(s, " {}", sci(v, 4));
                }
            }
            s.push('\n');
        }
    }
    s.push_str("\n\n\tR E A C T I O N S  O U T P U T:\n\t_______________________________\n\n\n");
    let mut rows: Vec<(usize, u8, usize, f64)> = res
        .dofs
        .prescribed
        .iter()
        .zip(res.reactions)
        .filter(|((n, _, _), _)| model.output.node(n + 1))
        .map(|(&(n, d, bi), &r)| (n, d, model.dirichlet[bi].number, r))
        .collect();
    rows.sort_by_key(|r| (r.0, r.1));
    for (n, d, bc, r) in rows {
        let _ = writeln!(
            s,
            "\tNode {:8} iDof {:2} reaction {}    [bc-id: {}]",
            model.nodes[n].label,
            d,
            sci_sign(r, 4),
            bc
        );
    }
    if !res.contact.is_empty() {
        s.push_str(&contact_table(model, res));
    }
    let _ = write!(
        s,
        "\nUser time consumed by solution step {}: {:.3} [s]\n\n",
        res.step, res.info.wall_seconds
    );
    s
}

/// The contact table of a step: one row per contact node.
fn contact_table(model: &Model, res: &StepResult) -> String {
    let mut s =
        String::from("\n\n\tC O N T A C T   O U T P U T:\n\t___________________________\n\n");
    s.push_str("\tcondition     node          gap         force      pressure  active\n");
    for c in res.contact {
        let _ = writeln!(
            s,
            "\t{:9} {:8} {} {} {} {:>7}",
            c.condition,
            model.nodes[c.node].label,
            sci_sign(c.gap, 4),
            sci_sign(c.force, 4),
            sci_sign(c.pressure, 4),
            if c.active { "yes" } else { "no" }
        );
    }
    s
}

/// The `.contact.csv` header (one row per contact node and step).
pub const CONTACT_CSV_HEADER: &str = "step,condition,node,x,y,z,gap,force,pressure,active";

/// CSV rows of one step's contact states.
pub fn contact_csv_rows(model: &Model, res: &StepResult) -> String {
    let mut s = String::new();
    for c in res.contact {
        let _ = writeln!(
            s,
            "{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{}",
            res.step,
            c.condition,
            model.nodes[c.node].label,
            c.x[0],
            c.x[1],
            c.x[2],
            c.gap,
            c.force,
            c.pressure,
            u8::from(c.active)
        );
    }
    s
}

/// Columns of the per-step history CSV: the step, its Newton effort, and for every DOF a
/// `BoundaryCondition` prescribes, the mean prescribed value and the summed reaction.
pub fn history_csv_header(model: &Model, dofs: &DofMap) -> String {
    let mut s = String::from("step,time,iterations,substeps,residual");
    for (bc, d) in prescribed_groups(dofs) {
        let n = model.dirichlet[bc].number;
        let _ = write!(s, ",bc{n}.u{d},bc{n}.r{d}");
    }
    s.push('\n');
    s
}

/// The (Dirichlet index, DOF id) pairs of the prescribed DOFs, in first-seen order.
fn prescribed_groups(dofs: &DofMap) -> Vec<(usize, DofId)> {
    let mut groups = Vec::new();
    for &(_, d, bc) in &dofs.prescribed {
        if !groups.contains(&(bc, d)) {
            groups.push((bc, d));
        }
    }
    groups
}

/// One row of the history CSV (see [`history_csv_header`]).
pub fn history_csv_row(res: &StepResult) -> String {
    let info = res.info;
    let mut s = format!(
        "{},{:e},{},{},{:e}",
        res.step,
        res.time,
        info.iterations,
        info.substeps,
        info.residual_history.last().copied().unwrap_or(0.0)
    );
    let nf = res.dofs.n_free;
    for (bc, d) in prescribed_groups(res.dofs) {
        let (mut u, mut r, mut n) = (0.0, 0.0, 0usize);
        for (i, &(_, di, bi)) in res.dofs.prescribed.iter().enumerate() {
            if (bi, di) == (bc, d) {
                u += res.u[nf + i];
                r += res.reactions[i];
                n += 1;
            }
        }
        let _ = write!(s, ",{:e},{:e}", u / n as f64, r);
    }
    s.push('\n');
    s
}

/// Header of the Newton residual CSV.
pub const NEWTON_CSV_HEADER: &str = "step,iteration,residual";

/// Rows of the Newton residual CSV: the step's residual history, iteration 0 first.
pub fn newton_csv_rows(res: &StepResult) -> String {
    let mut s = String::new();
    for (k, r) in res.info.residual_history.iter().enumerate() {
        let _ = writeln!(s, "{},{k},{r:e}", res.step);
    }
    s
}

/// C `%.Ne` formatting (exponent with sign and at least two digits).
pub fn sci(v: f64, prec: usize) -> String {
    if !v.is_finite() {
        return if v.is_nan() {
            "nan".into()
        } else if v > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let s = format!("{v:.prec$e}");
    let (mant, exp) = s.split_once('e').expect("exponent");
    let e: i32 = exp.parse().expect("integer exponent");
    format!("{mant}e{}{:02}", if e < 0 { '-' } else { '+' }, e.abs())
}

/// C `% .Ne` (a space in place of the plus sign).
pub fn sci_sign(v: f64, prec: usize) -> String {
    let s = sci(v, prec);
    if v < 0.0 || s.starts_with('-') {
        s
    } else {
        format!(" {s}")
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn sci_matches_c_printf() {
        assert_eq!(super::sci(-1.5625, 8), "-1.56250000e+00");
        assert_eq!(super::sci(4.975e6, 4), "4.9750e+06");
        assert_eq!(super::sci(1.2e-12, 4), "1.2000e-12");
        assert_eq!(super::sci(f64::NAN, 4), "nan");
        assert_eq!(super::sci(f64::NEG_INFINITY, 4), "-inf");
    }
}
