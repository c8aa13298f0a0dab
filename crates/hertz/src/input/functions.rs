//! The time-function block.

use super::cursor::{Block, Cursor, Numbered};
use crate::error::Result;
use crate::model::*;

/// The time-function records.
pub(super) fn read_time_functions(c: &mut Cursor, nltf: usize) -> Result<Vec<TimeFunction>> {
    let mut funcs = Numbered::new("time function", nltf);
    for i in 0..nltf {
        let r = c.next_of(Block::TimeFunction, i, nltf)?;
        let f = match r.keyword() {
            "constantfunction" => TimeFunction::Constant(r.float("f(t)")?),
            "peakfunction" => TimeFunction::Peak { t: r.float("t")?, value: r.float("f(t)")? },
            "piecewiselinfunction" => {
                if r.flag("datafile") {
                    return Err(r.error("PiecewiseLinFunction `datafile` is not supported; list t and f(t)"));
                }
                let npoints = r.opt_usize("npoints")?;
                let t = r.float_array("t")?;
                let f = r.float_array("f(t)")?;
                if t.is_empty() || t.len() != f.len() {
                    return Err(r.error(format!("`t` has {} points and `f(t)` {}: they must match", t.len(), f.len())));
                }
                if npoints.is_some_and(|n| n != t.len()) {
                    return Err(r.error(format!(
                        "`npoints {}` but `t` and `f(t)` have {} points: they must match",
                        npoints.unwrap_or(0),
                        t.len()
                    )));
                }
                if t.windows(2).any(|w| w[1] <= w[0]) {
                    return Err(r.error("`t` must be strictly increasing"));
                }
                TimeFunction::PiecewiseLinear { t, f }
            }
            k => {
                return Err(r.error(format!(
                    "unsupported time function `{k}`; supported: ConstantFunction, PiecewiseLinFunction, PeakFunction"
                )))
            }
        };
        funcs.put(&r, f)?;
        c.finish(&r);
    }
    let functions = funcs.finish();

    Ok(functions)
}
