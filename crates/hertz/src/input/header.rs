//! The first records: output file, description, analysis, domain, output manager and the counts.

use super::cursor::Cursor;
use super::record::Record;
use crate::error::Result;
use crate::model::*;

/// Upper bound on the number of steps (guards allocations against absurd inputs).
pub(super) const MAX_STEPS: usize = 10_000_000;

pub(super) const SUPPORTED_ANALYSES: &str =
    "LinearStatic, NonLinearStatic, StaticStructural, NonLinearDynamic, DIIDynamic, NlDEIDynamic";

/// The records before the counts: the engineering model (with its modules), the domain and the
/// output manager.
pub(super) fn read_header(c: &mut Cursor) -> Result<(Analysis, DomainKind, OutputSelection)> {
    let file = c.file.clone();
    let r = c.next("the engineering-model record (e.g. StaticStructural nsteps 1)")?;
    let (mut analysis, nmodules, ninit, nmonitors) = read_analysis(&r)?;
    c.finish(&r);
    for i in 0..ninit {
        let r = c.next(&format!("init module record {} of {ninit}", i + 1))?;
        c.warnings.push(format!(
            "{}:{}: init module `{}` ignored",
            file,
            r.line.line,
            r.keyword()
        ));
    }
    for i in 0..nmodules {
        let r = c.next(&format!("export module record {} of {nmodules}", i + 1))?;
        if r.keyword() == "errorcheck" {
            analysis.errorcheck = true;
        } else {
            c.warnings.push(format!(
                "{}:{}: export module `{}` ignored",
                file,
                r.line.line,
                r.keyword()
            ));
        }
    }
    for i in 0..nmonitors {
        let r = c.next(&format!("monitor record {} of {nmonitors}", i + 1))?;
        c.warnings.push(format!(
            "{}:{}: monitor `{}` ignored",
            file,
            r.line.line,
            r.keyword()
        ));
    }

    // Domain record.
    let r = c.next("the domain record (e.g. domain 2dPlaneStress)")?;
    let domain = read_domain(&r)?;
    c.finish(&r);

    // Output manager.
    let r = c.next("the OutputManager record")?;
    if r.keyword() != "outputmanager" {
        return Err(r.error(format!(
            "expected the OutputManager record, found `{}`",
            r.keyword()
        )));
    }
    let left_records = c.lines.len() - c.pos;
    let output = OutputSelection {
        tstep_all: r.flag("tstep_all"),
        tstep_step: r.opt_usize("tstep_step")?,
        tsteps_out: r
            .opt_range_list("tsteps_out", MAX_STEPS)?
            .unwrap_or_default(),
        dofman_all: r.flag("dofman_all"),
        dofman_output: r
            .opt_range_list("dofman_output", left_records)?
            .unwrap_or_default(),
        dofman_except: r
            .opt_range_list("dofman_except", left_records)?
            .unwrap_or_default(),
        element_all: r.flag("element_all"),
        element_output: r
            .opt_range_list("element_output", left_records)?
            .unwrap_or_default(),
        element_except: r
            .opt_range_list("element_except", left_records)?
            .unwrap_or_default(),
    };
    c.finish(&r);

    Ok((analysis, domain, output))
}

/// The counts record: how many records of each block follow.
pub(super) struct Counts {
    pub(super) ndofman: usize,
    pub(super) nelem: usize,
    pub(super) ncs: usize,
    pub(super) nmat: usize,
    pub(super) nbc: usize,
    pub(super) nic: usize,
    pub(super) nltf: usize,
    pub(super) nset: usize,
    pub(super) ncontactseg: usize,
    pub(super) ncontactsurf: usize,
}

/// The counts record, each count checked against the records left.
pub(super) fn read_counts(c: &mut Cursor) -> Result<Counts> {
    let r = c.next("the counts record (ndofman nelem ncrosssect nmat nbc nic nltf ...)")?;
    r.keyword();
    let n = Counts {
        ndofman: r.usize("ndofman")?,
        nelem: r.usize("nelem")?,
        ncs: r.usize("ncrosssect")?,
        nmat: r.usize("nmat")?,
        nbc: r.usize("nbc")?,
        nic: r.usize("nic")?,
        nltf: r.usize("nltf")?,
        nset: r.opt_usize("nset")?.unwrap_or(0),
        ncontactseg: r.opt_usize("ncontactseg")?.unwrap_or(0),
        ncontactsurf: r.opt_usize("ncontactsurf")?.unwrap_or(0),
    };
    let left = c.lines.len() - c.pos;
    for (k, v) in [
        ("ndofman", n.ndofman),
        ("nelem", n.nelem),
        ("ncrosssect", n.ncs),
        ("nmat", n.nmat),
        ("nbc", n.nbc),
        ("nic", n.nic),
        ("nltf", n.nltf),
        ("nset", n.nset),
        ("ncontactseg", n.ncontactseg),
        ("ncontactsurf", n.ncontactsurf),
    ] {
        if v > left {
            return Err(r.error(format!(
                "`{k} {v}` is more than the {left} records left in the file"
            )));
        }
    }
    for k in ["nsd", "nbarrier", "nxfemman", "ncontactman", "nfracman"] {
        if r.opt_usize(k)?.unwrap_or(0) > 0 && k != "nsd" {
            return Err(r.error(format!("`{k}` > 0 is not supported by hertz")));
        }
    }
    r.flag("axisymm");
    c.finish(&r);

    Ok(n)
}

pub(super) fn read_analysis(r: &Record) -> Result<(Analysis, usize, usize, usize)> {
    let kind = match r.keyword() {
        "linearstatic" => AnalysisKind::LinearStatic,
        "nonlinearstatic" => AnalysisKind::NonLinearStatic,
        "staticstructural" => AnalysisKind::StaticStructural,
        "nonlineardynamic" => AnalysisKind::NonLinearDynamic,
        "diidynamic" => AnalysisKind::DIIDynamic,
        "nldeidynamic" => AnalysisKind::NlDEIDynamic,
        k => {
            return Err(r.error(format!(
                "unsupported analysis type `{k}`; supported: {SUPPORTED_ANALYSES}"
            )));
        }
    };
    let prescribed_times = if kind == AnalysisKind::StaticStructural {
        r.opt_float_array("prescribedtimes")?
    } else {
        None
    };
    let nsteps = match (&prescribed_times, r.opt_usize("nsteps")?) {
        (Some(t), _) => t.len(),
        (None, Some(n)) => n,
        (None, None) => return Err(r.error("missing required keyword `nsteps`")),
    };
    if nsteps == 0 {
        return Err(r.error("`nsteps` must be positive"));
    }
    if nsteps > MAX_STEPS {
        return Err(r.error(format!(
            "`nsteps {nsteps}` is more than hertz runs ({MAX_STEPS})"
        )));
    }
    if r.opt_usize("nmsteps")?.unwrap_or(0) > 0 {
        return Err(r.error("metasteps (`nmsteps` > 0) are not supported"));
    }
    if kind == AnalysisKind::NonLinearStatic {
        let mode = match r.opt_int("controlmode")? {
            Some(m) => Some(m),
            None => r.opt_int("controllmode")?,
        };
        if mode.unwrap_or(0) != 1 {
            return Err(r.error(
                "NonLinearStatic needs `controlmode 1` (direct load control); indirect (arc-length) control is not supported",
            ));
        }
        if r.flag("deltatfunction") {
            return Err(r.error("`deltatfunction` is not supported"));
        }
    }
    if kind == AnalysisKind::DIIDynamic && r.opt_float("deltat")?.is_none() {
        return Err(r.error("DIIDynamic needs `deltat` (the time step)"));
    }
    let deltat = r.opt_float("deltat")?.unwrap_or(1.0);
    if !(deltat > 0.0) {
        return Err(r.error("`deltat` must be positive"));
    }
    let rtolv = r.opt_float("rtolv")?;
    let rtolf = r.opt_float("rtolf")?.or(rtolv).unwrap_or(1e-3);
    let rtold = r.opt_float("rtold")?.or(rtolv).unwrap_or(0.0);
    let maxiter = r.opt_usize("maxiter")?.unwrap_or(50);
    if maxiter == 0 {
        return Err(r.error("`maxiter` must be at least 1"));
    }
    let manrmsteps = r.opt_usize("manrmsteps")?.filter(|&k| k > 0);
    let refloadmode = match r.opt_int("refloadmode")?.unwrap_or(0) {
        v @ (0 | 1) => v as u8,
        v => return Err(r.error(format!("`refloadmode` must be 0 or 1, found {v}"))),
    };
    let initialguess = r.opt_int("initialguess")?.map(|v| v != 0);
    for k in [
        "renumber",
        "lstype",
        "smtype",
        "stiffmode",
        "miniter",
        "nonlinform",
        "contextoutputstep",
        "profileopt",
    ] {
        r.opt_int(k)?;
    }
    r.opt_string("solvertype")?;
    for k in [
        "soldepextforces",
        "suppress_output",
        "keepll",
        "donotfixload",
    ] {
        r.flag(k);
    }
    let dynamics = match kind {
        AnalysisKind::NonLinearDynamic => Some(read_dynamics(r, "NonLinearDynamic")?),
        AnalysisKind::DIIDynamic => Some(read_dynamics(r, "DIIDynamic")?),
        AnalysisKind::NlDEIDynamic => Some(read_explicit(r)?),
        _ => None,
    };
    let nmodules = r.opt_usize("nmodules")?.unwrap_or(0);
    let ninit = r.opt_usize("ninitmodules")?.unwrap_or(0);
    let nmonitors = r.opt_usize("nmonitors")?.unwrap_or(0);
    let analysis = Analysis {
        kind,
        nsteps,
        deltat,
        prescribed_times,
        rtolf,
        rtold,
        maxiter,
        manrmsteps,
        refloadmode,
        initialguess,
        errorcheck: false,
        dynamics,
    };
    Ok((analysis, nmodules, ninit, nmonitors))
}

/// The time integration of `analysis` (`NonLinearDynamic` or `DIIDynamic`, spec §1.2–1.3):
/// `ddtScheme` (0 three-point backward, the default; 1 backward Euler; 2 Newmark with `gamma`,
/// `beta`), Rayleigh damping `eta` and `delta`, and hertz's `lumpedmass`.
fn read_dynamics(r: &Record, analysis: &str) -> Result<Dynamics> {
    let scheme = match r.opt_int("ddtscheme")?.unwrap_or(0) {
        0 => TimeScheme::ThreePointBackward,
        1 => TimeScheme::BackwardEuler,
        2 if r.opt_float("rhoinf")?.is_some() => {
            let rho = r.float("rhoinf")?;
            if !(0.5..=1.0).contains(&rho) {
                return Err(r.error(format!(
                    "`rhoinf` (HHT's spectral radius at high frequency) must be in [0.5, 1], \
                     found {rho}"
                )));
            }
            if r.opt_float("gamma")?.is_some() || r.opt_float("beta")?.is_some() {
                return Err(r.error(
                    "`rhoinf` sets HHT's gamma and beta: give `rhoinf` or `gamma` and `beta`",
                ));
            }
            TimeScheme::Hht {
                alpha: (rho - 1.0) / (rho + 1.0),
            }
        }
        2 => {
            let gamma = r.opt_float("gamma")?.unwrap_or(0.5);
            let beta = r.opt_float("beta")?.unwrap_or(0.25);
            if !(beta > 0.0 && gamma >= 0.5 && 2.0 * beta >= gamma) {
                return Err(r.error(format!(
                    "Newmark needs γ ≥ ½ and β ≥ γ/2 > 0 to be unconditionally stable, found γ \
                     {gamma}, β {beta}"
                )));
            }
            TimeScheme::Newmark { gamma, beta }
        }
        3 if analysis == "DIIDynamic" => {
            return Err(r.error(
                "`ddtScheme 3` (Wilson-θ) is not supported: 0 (three-point backward), 1 \
                 (backward Euler) or 2 (Newmark, or HHT-α with `rhoinf`)",
            ))
        }
        v => {
            return Err(r.error(format!(
                "`ddtScheme {v}` is not supported by {analysis}: 0 (three-point backward), 1 \
                 (backward Euler) or 2 (Newmark)"
            )))
        }
    };
    let eta = r.opt_float("eta")?.unwrap_or(0.0);
    if eta < 0.0 {
        return Err(r.error(format!(
            "`eta` (mass-proportional damping) must not be negative, found {eta}"
        )));
    }
    let delta = r.opt_float("delta")?.unwrap_or(0.0);
    if delta < 0.0 {
        return Err(r.error(format!(
            "`delta` (stiffness-proportional damping) must not be negative, found {delta}"
        )));
    }
    Ok(Dynamics {
        scheme,
        eta,
        delta,
        lumped: r.flag("lumpedmass"),
        keep_contact_mass: r.flag("keepcontactmass"),
    })
}

/// `NlDEIDynamic` (spec §1.4): central differences on the lumped mass, `deltat` and the damping
/// coefficient `dumpcoef` (C = c·M) required, `reduct` the safety factor on the stable step.
fn read_explicit(r: &Record) -> Result<Dynamics> {
    if r.opt_float("deltat")?.is_none() {
        return Err(r.error("NlDEIDynamic needs `deltat`"));
    }
    let eta = r.float("dumpcoef")?;
    if eta < 0.0 {
        return Err(r.error(format!("`dumpcoef` must not be negative, found {eta}")));
    }
    let reduct = r.opt_float("reduct")?.unwrap_or(1.0);
    if !(reduct > 0.0 && reduct <= 1.0) {
        return Err(r.error(format!(
            "`reduct` (the fraction of the stable time step) must be in (0, 1], found {reduct}"
        )));
    }
    if r.opt_int("drflag")?.unwrap_or(0) != 0 {
        return Err(r.error("dynamic relaxation (`drflag` 1) is not supported"));
    }
    r.opt_float("tau")?;
    r.opt_float("py")?;
    Ok(Dynamics {
        scheme: TimeScheme::CentralDifference { reduct },
        eta,
        delta: 0.0,
        lumped: true,
        keep_contact_mass: true,
    })
}

pub(super) fn read_domain(r: &Record) -> Result<DomainKind> {
    let i = r.tokens.iter().position(|t| t == "domain").ok_or_else(|| {
        r.error(format!(
            "expected the domain record (e.g. `domain 2dPlaneStress`), found `{}`",
            r.keyword()
        ))
    })?;
    r.flag("domain");
    r.opt_string("domain")?;
    let t = r.tokens.get(i + 1).map(String::as_str).unwrap_or("");
    let kind = if t.starts_with("2dplanestressrot") {
        None
    } else if t.starts_with("2dplanestress") {
        Some(DomainKind::PlaneStress)
    } else if t.starts_with("planestrain") {
        Some(DomainKind::PlaneStrain)
    } else if t.starts_with("2dtruss") {
        Some(DomainKind::Truss2d)
    } else if t.starts_with("1dtruss") {
        Some(DomainKind::Truss1d)
    } else if t.starts_with("3d") && !t.starts_with("3daxisymm") && !t.starts_with("3dshell") {
        Some(DomainKind::ThreeD)
    } else {
        None
    };
    kind.ok_or_else(|| {
        r.error(format!("unsupported domain type `{t}`; supported: 2dPlaneStress, PlaneStrain, 3d, 2dTruss, 1dTruss"))
    })
}
