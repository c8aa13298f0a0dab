//! The boundary-condition block: prescribed values, loads and contact conditions.

use super::cursor::{check_ref, Block, Cursor, Numbered};
use super::header::Counts;
use super::keywords::supported_conditions;
use super::record::Record;
use crate::error::Result;
use crate::model::*;
use std::collections::HashMap;

/// The boundary-condition block: Dirichlet conditions, loads, and contact conditions still to be
/// resolved against sets and segments.
pub(super) struct Conditions {
    pub(super) dirichlet: Vec<Dirichlet>,
    pub(super) loads: Vec<Load>,
    pub(super) pending_penalty_bcs: Vec<super::upstream::PendingPenaltyBc>,
    pub(super) pending_contacts: Vec<super::contact::PendingCondition>,
}

/// The boundary-condition, load and contact-condition records.
pub(super) fn read_conditions(
    c: &mut Cursor,
    n: &Counts,
    analysis: &Analysis,
    domain: &DomainKind,
    node_index: &HashMap<usize, usize>,
) -> Result<Conditions> {
    let (nbc, nltf, nset, ncontactsurf, ncontactseg) =
        (n.nbc, n.nltf, n.nset, n.ncontactsurf, n.ncontactseg);
    let mut pending_penalty_bcs = Vec::new();
    let mut pending_contacts = Vec::new();
    let mut bcs: Numbered<Option<Dirichlet>> = Numbered::new("boundary condition", nbc);
    let mut loads = Vec::new();
    for i in 0..nbc {
        let r = c.next_of(Block::Condition, i, nbc)?;
        let kw = r.keyword().to_string();
        let number = r.number()?;
        let function = r.usize("loadtimefunction")?;
        if function == 0 || function > nltf {
            return Err(r.error(format!(
                "loadTimeFunction {function} does not exist (nltf {nltf})"
            )));
        }
        let set = r.opt_usize("set")?.unwrap_or(0);
        check_ref(&r, "set", Some(set).filter(|&s| s > 0), nset)?;
        if r.flag("istimefunction") || r.flag("isimposedtimefunction") {
            return Err(r.error("`isImposedTimeFunction` is not supported"));
        }
        r.opt_usize("valtype")?;
        match kw.as_str() {
            "boundarycondition" => {
                let d = read_dirichlet(&r, number, function, set, domain)?;
                bcs.put(&r, Some(d))?;
            }
            "nodalload"
            | "constantedgeload"
            | "constantsurfaceload"
            | "constantpressureload"
            | "deadweight" => {
                loads.push(read_load(&r, &kw, number, function, set, domain)?);
                bcs.put(&r, None)?;
            }
            "structuralpenaltycontactbc" => {
                if analysis.kind == AnalysisKind::LinearStatic {
                    return Err(r.error(
                        "contact needs NonLinearStatic or StaticStructural, not LinearStatic",
                    ));
                }
                pending_penalty_bcs.push(super::upstream::read_penalty_bc(
                    &r,
                    domain.nsd(),
                    ncontactsurf,
                )?);
                bcs.put(&r, None)?;
            }
            k if super::contact::CONDITION_KEYWORDS.contains(&k) => {
                if analysis.kind == AnalysisKind::LinearStatic {
                    return Err(r.error(
                        "contact needs NonLinearStatic or StaticStructural, not LinearStatic",
                    ));
                }
                pending_contacts.push(super::contact::read_condition(
                    &r,
                    node_index,
                    domain.nsd(),
                    nset,
                    ncontactseg,
                )?);
                bcs.put(&r, None)?;
            }
            _ => {
                return Err(r.error(format!(
                    "unsupported boundary condition or load `{kw}`; supported: {}",
                    supported_conditions()
                )))
            }
        }
        c.finish(&r);
    }
    let dirichlet: Vec<Dirichlet> = bcs.finish().into_iter().flatten().collect();

    Ok(Conditions {
        dirichlet,
        loads,
        pending_penalty_bcs,
        pending_contacts,
    })
}

/// The DOF ids a `dofs` array names (displacements only), if it is there.
pub(super) fn read_dofs(r: &Record) -> Result<Option<Vec<DofId>>> {
    match r.opt_int_array("dofs")? {
        None => Ok(None),
        Some(v) => v
            .iter()
            .map(|&d| {
                if (1..=3).contains(&d) {
                    Ok(d as DofId)
                } else {
                    Err(r.error(format!("DOF id {d} is not a displacement DOF (1, 2 or 3)")))
                }
            })
            .collect::<Result<Vec<_>>>()
            .map(Some),
    }
}

/// A `BoundaryCondition` record: prescribed values of DOFs on a set's nodes.
pub(super) fn read_dirichlet(
    r: &Record,
    number: usize,
    function: usize,
    set: usize,
    domain: &DomainKind,
) -> Result<Dirichlet> {
    let dofs = read_dofs(r)?.unwrap_or_else(|| domain.default_dofs().to_vec());
    let values = match r.opt_float_array("values")? {
        Some(v) => v,
        None => {
            let v = match r.opt_float("prescribedvalue")? {
                Some(v) => v,
                None => r
                    .opt_float("d")?
                    .ok_or_else(|| r.error("BoundaryCondition needs `values`"))?,
            };
            vec![v; dofs.len()]
        }
    };
    if values.len() != dofs.len() {
        return Err(r.error(format!(
            "`values` has {} entries for {} dofs",
            values.len(),
            dofs.len()
        )));
    }
    Ok(Dirichlet {
        number,
        function,
        dofs,
        values,
        set: Some(set).filter(|&s| s > 0),
        span: r.span(),
    })
}

/// A load record (`NodalLoad`, `ConstantEdgeLoad`, `ConstantSurfaceLoad`, `DeadWeight`).
pub(super) fn read_load(
    r: &Record,
    kw: &str,
    number: usize,
    function: usize,
    set: usize,
    domain: &DomainKind,
) -> Result<Load> {
    let kind = match kw {
        "nodalload" => LoadKind::Nodal,
        "constantedgeload" => LoadKind::Edge,
        "deadweight" => LoadKind::DeadWeight,
        _ => LoadKind::Surface,
    };
    if kw == "constantpressureload" {
        return Err(r.error("ConstantPressureLoad is not supported; use ConstantSurfaceLoad"));
    }
    let components = r.float_array("components")?;
    let dofs = match (&kind, read_dofs(r)?) {
        (_, Some(d)) => d,
        (LoadKind::DeadWeight, None) => (1..=components.len() as DofId).collect(),
        (_, None) => domain.default_dofs().to_vec(),
    };
    if components.len() != dofs.len() {
        return Err(r.error(format!(
            "`components` has {} entries for {} dofs",
            components.len(),
            dofs.len()
        )));
    }
    let nsd = domain.nsd();
    let local =
        match r.opt_int("cstype")?.unwrap_or(0) {
            0 => false,
            1 => match kind {
                LoadKind::Edge if nsd == 2 && dofs == [1, 2] => true,
                LoadKind::Surface if nsd == 3 && dofs == [1, 2, 3] => true,
                _ => return Err(r.error(
                    "`cstype 1` (components in the boundary's own axes) is supported on 2D edge \
                     loads with `dofs 2 1 2` and on 3D surface loads with `dofs 3 1 2 3`",
                )),
            },
            v => return Err(r.error(format!("`cstype` must be 0 or 1, found {v}"))),
        };
    let follower = r.flag("follower");
    if follower && !local {
        return Err(r.error(
            "`follower` needs `cstype 1`: a follower traction is given in the boundary's own axes",
        ));
    }
    if follower && nsd == 3 && (components[0] != 0.0 || components[1] != 0.0) {
        return Err(r.error(
            "a `follower` surface load is a pressure: its components in the face's plane must \
             be 0 (`components 3 0 0 p`, p along the outward normal)",
        ));
    }
    r.opt_int("loadtype")?;
    if set == 0 && !matches!(kind, LoadKind::Edge | LoadKind::Surface) {
        return Err(r.error(format!("{kw} needs `set`")));
    }
    Ok(Load {
        number,
        kind,
        function,
        dofs,
        components,
        set,
        local,
        follower,
        span: r.span(),
    })
}

/// The initial-condition records (`nic` of them): `InitialCondition n conditions k <L> <value>
/// … set s dofs m id…`, L = u (displacement), v (velocity) or a (acceleration) (spec §1.6).
pub(super) fn read_initial_conditions(
    c: &mut Cursor,
    nic: usize,
    nset: usize,
    analysis: &Analysis,
) -> Result<Vec<InitialCondition>> {
    let mut out = Vec::with_capacity(nic);
    for i in 0..nic {
        let r = c.next_of(Block::InitialCondition, i, nic)?;
        if r.keyword() != "initialcondition" {
            return Err(r.error(format!(
                "expected an InitialCondition record, found `{}`",
                r.keyword()
            )));
        }
        let number = r.number()?;
        if number != i + 1 {
            return Err(r.error(format!(
                "initial conditions are numbered 1..{nic} in order, found {number} in place {}",
                i + 1
            )));
        }
        if analysis.dynamics.is_none() {
            return Err(r.error(
                "initial conditions need a dynamic analysis (NonLinearDynamic, DIIDynamic, NlDEIDynamic); a static one \
                 starts from rest",
            ));
        }
        if r.opt_string("f")?.is_some() || r.opt_string("field")?.is_some() {
            return Err(r.error(
                "only the `conditions k <u|v|a> value …` form of InitialCondition is supported",
            ));
        }
        let Some(pairs) = r.opt_tagged_values("conditions")? else {
            return Err(r.error("InitialCondition needs `conditions k <u|v|a> value …`"));
        };
        let (mut displacement, mut velocity, mut acceleration) = (None, None, None);
        for (tag, value) in pairs {
            let slot = match tag.chars().next() {
                Some('u') => &mut displacement,
                Some('v') => &mut velocity,
                Some('a') => &mut acceleration,
                _ => {
                    return Err(r.error(format!(
                        "initial condition `{tag}`: the kind is u (displacement), v (velocity) or \
                         a (acceleration) (OOFEM ignores others silently)"
                    )))
                }
            };
            *slot = Some(value);
        }
        let set = r.usize("set")?;
        check_ref(&r, "set", Some(set), nset)?;
        let dofs = r
            .int_array("dofs")?
            .into_iter()
            .map(|d| match d {
                1..=3 => Ok(d as DofId),
                _ => Err(r.error(format!(
                    "DOF {d} in `dofs` is not a displacement (1, 2 or 3)"
                ))),
            })
            .collect::<Result<Vec<_>>>()?;
        r.opt_int("valtype")?;
        c.finish(&r);
        out.push(InitialCondition {
            number,
            set,
            dofs,
            displacement,
            velocity,
            acceleration,
            span: r.span(),
        });
    }
    Ok(out)
}
