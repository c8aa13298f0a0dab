//! The OOFEM-style `.out` text file (spec §4): per step the DOF values of the selected nodes, the
//! integration-point strains and stresses (or F and P for `nlgeo 1`), and the reaction table.

use super::number::{push_sci, push_sci_sign, sci, sci_sign};
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

/// The date as C's `ctime` writes it (OOFEM's header), in UTC: `Sun Nov 22 18:10:12 2026`.
fn timestamp() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    ctime_utc(secs)
}

/// `ctime` of `secs` since the Unix epoch, in UTC (days to civil date: H. Hinnant's algorithm).
pub fn ctime_utc(secs: u64) -> String {
    const DAYS: [&str; 7] = ["Thu", "Fri", "Sat", "Sun", "Mon", "Tue", "Wed"];
    const MONTHS: [&str; 12] = [
        "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
    ];
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{} {} {:2} {:02}:{:02}:{:02} {year}",
        DAYS[days.rem_euclid(7) as usize],
        MONTHS[month as usize - 1],
        day,
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// The block of one step, in pieces to be written one after the other (the node and element
/// lists of a large model are tens of megabytes: not copied into one string).
pub fn step_block(model: &Model, res: &StepResult) -> Vec<String> {
    let mut parts = Vec::new();
    let mut s = String::new();
    match model.analysis.kind {
        AnalysisKind::NonLinearDynamic => {
            let _ = write!(
                s,
                "\n\nOutput for time {}, solution step number {}\nEquilibrium reached in {} iterations\n\n",
                sci(res.time, 3), res.step, res.info.iterations
            );
        }
        AnalysisKind::NonLinearStatic => {
            let _ = write!(
                s,
                "\n\nOutput for time {}, solution step number {}\nReached load level : {:20.6} in {} iterations\n\n",
                sci(res.time, 3), res.step, 1.0, res.info.iterations
            );
        }
        _ => {
            let _ = write!(
                s,
                "\n==============================================================\nOutput for time {} \n\
                 ==============================================================\nOutput for domain   1\n",
                sci(res.time, 8)
            );
        }
    }
    s.push_str("\n\nDofManager output:\n------------------\n");
    parts.push(std::mem::take(&mut s));
    parts.extend(par_blocks(model.nodes.len(), |n, s| {
        node_block(model, res, n, s)
    }));
    s.push_str("\n\nElement output:\n---------------\n");
    parts.push(std::mem::take(&mut s));
    parts.extend(par_blocks(model.elements.len(), |e, s| {
        element_block(model, res, e, s)
    }));
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
    parts.push(s);
    parts
}

/// The blocks of items 0..n in order, formatted in parallel chunks.
fn par_blocks(n: usize, block: impl Fn(usize, &mut String) + Sync) -> Vec<String> {
    use rayon::prelude::*;
    const CHUNK: usize = 2048;
    (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| {
            let (start, end) = (c * CHUNK, ((c + 1) * CHUNK).min(n));
            let mut s = String::new();
            block(start, &mut s);
            // The first block's length sizes the chunk's string: no growing copies.
            s.reserve((s.len() + s.len() / 8) * (end - start - 1));
            for i in start + 1..end {
                block(i, &mut s);
            }
            s
        })
        .collect()
}

/// One node's DOF values (if the output manager selects it).
fn node_block(model: &Model, res: &StepResult, n: usize, s: &mut String) {
    if !model.output.node(n + 1) {
        return;
    }
    let node = &model.nodes[n];
    let class = if node.slave.is_some() {
        "SlaveNode"
    } else {
        "Node"
    };
    s.push_str(class);
    s.push_str(&"        "[class.len().min(8)..]);
    push_int(s, node.label, 8);
    s.push_str(" (");
    push_int(s, n + 1, 8);
    s.push_str("):\n");
    for &(d, code) in &res.dofs.node_dofs[n] {
        s.push_str("  dof ");
        push_int(s, usize::from(d), 0);
        s.push_str("   d ");
        push_sci_sign(s, res.dofs.value(res.u, code), 8);
        if let Some(m) = &res.motion {
            // Dynamics (spec §1.1): `dof k   d u   v v   a a`.
            s.push_str("   v ");
            push_sci_sign(s, res.dofs.value(m.velocity, code), 8);
            s.push_str("   a ");
            push_sci_sign(s, res.dofs.value(m.acceleration, code), 8);
        }
        s.push('\n');
    }
}

/// Append `v` right-aligned in `width` columns (`{:width$}` without the formatting machinery).
fn push_int(s: &mut String, v: usize, width: usize) {
    let mut buf = [b' '; 24];
    let mut at = buf.len();
    let mut m = v;
    loop {
        at -= 1;
        buf[at] = b'0' + (m % 10) as u8;
        m /= 10;
        if m == 0 {
            break;
        }
    }
    let at = at.min(buf.len().saturating_sub(width));
    s.push_str(std::str::from_utf8(&buf[at..]).expect("ASCII"));
}

/// One element's integration-point strains and stresses (F and P with `nlgeo 1`).
fn element_block(model: &Model, res: &StepResult, e: usize, s: &mut String) {
    if !model.output.element(e + 1) {
        return;
    }
    let el = &model.elements[e];
    s.push_str("element ");
    push_int(s, el.label, 0);
    s.push_str(" (");
    push_int(s, e + 1, 8);
    s.push_str(") :\n");
    for (g, st) in res.states[e].iter().enumerate() {
        // "  GP  1.g  :" with g left-aligned in two columns.
        s.push_str("  GP  1.");
        push_int(s, g + 1, 0);
        s.push_str(if g + 1 < 10 { "  :" } else { " :" });
        let values = |s: &mut String, v: &mut dyn Iterator<Item = f64>| {
            for x in v {
                s.push(' ');
                push_sci(s, x, 4);
            }
        };
        if el.nlgeo {
            const ORDER: [(usize, usize); 9] = [
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
            values(s, &mut ORDER.iter().map(|&(i, j)| st.f[i][j]));
            s.push_str("\n  P");
            values(s, &mut ORDER.iter().map(|&(i, j)| st.p[i][j]));
        } else {
            s.push_str("  strains ");
            values(s, &mut st.strain.iter().copied());
            s.push_str("\n              stresses");
            values(s, &mut st.stress.iter().copied());
        }
        s.push('\n');
        if let Some(p) = &st.plastic {
            // As OOFEM's MisesMat prints its status.
            s.push_str("              plastic  ");
            for &x in &p.strain {
                push_sci(s, x, 4);
                s.push(' ');
            }
            s.push_str("\nstatus { damage ");
            push_sci(s, p.damage, 4);
            s.push_str(", kappa  ");
            push_sci(s, p.kappa, 4);
            s.push_str("}\n");
        }
    }
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
pub const CONTACT_CSV_HEADER: &str =
    "step,condition,node,x,y,z,gap,force,pressure,active,friction,slip";

/// CSV rows of one step's contact states.
pub fn contact_csv_rows(model: &Model, res: &StepResult) -> String {
    let mut s = String::new();
    for c in res.contact {
        let _ = writeln!(
            s,
            "{},{},{},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e},{}",
            res.step,
            c.condition,
            model.nodes[c.node].label,
            c.x[0],
            c.x[1],
            c.x[2],
            c.gap,
            c.force,
            c.pressure,
            u8::from(c.active),
            c.friction.map_or(0.0, |f| f.1),
            u8::from(c.friction.is_some_and(|f| !f.0))
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

/// The (Dirichlet index, DOF id) pairs of the prescribed DOFs, in the input's order of the
/// conditions, each by DOF id.
fn prescribed_groups(dofs: &DofMap) -> Vec<(usize, DofId)> {
    let mut groups: Vec<(usize, DofId)> =
        dofs.prescribed.iter().map(|&(_, d, bc)| (bc, d)).collect();
    groups.sort_unstable();
    groups.dedup();
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

/// Header of the energy CSV of a dynamic analysis (see [`crate::solve::Energy`]).
pub const ENERGY_CSV_HEADER: &str =
    "step,time,kinetic,internal,contact,damping,external,supports,balance";

/// The energy CSV's row of a dynamic step (empty for a static one).
pub fn energy_csv_row(res: &StepResult) -> String {
    let Some(m) = &res.motion else {
        return String::new();
    };
    let e = &m.energy;
    format!(
        "{},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e}\n",
        res.step,
        res.time,
        e.kinetic,
        e.internal,
        e.contact,
        e.damping,
        e.external,
        e.supports,
        e.balance()
    )
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

#[cfg(test)]
mod tests {
    /// Dates as `date -u -d @SECS '+%a %b %e %T %Y'` prints them (C's ctime layout).
    #[test]
    fn ctime_matches_the_c_library() {
        assert_eq!(super::ctime_utc(0), "Thu Jan  1 00:00:00 1970");
        assert_eq!(super::ctime_utc(951_782_400), "Tue Feb 29 00:00:00 2000");
        assert_eq!(super::ctime_utc(1_795_370_501), "Sun Nov 22 18:01:41 2026");
        assert_eq!(super::ctime_utc(4_107_542_399), "Sun Feb 28 23:59:59 2100");
    }
}
