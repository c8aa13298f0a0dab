//! The node block: `Node` and `SlaveNode` records.

use super::cursor::{Block, Cursor};
use super::record::Record;
use crate::error::{Error, Result};
use crate::model::*;
use std::collections::HashMap;

/// The node records (`Node`, `SlaveNode`), with the index of each label.
pub(super) fn read_nodes(
    c: &mut Cursor,
    ndofman: usize,
) -> Result<(Vec<Node>, HashMap<usize, usize>)> {
    let mut nodes = Vec::with_capacity(ndofman);
    let mut node_index: HashMap<usize, usize> = HashMap::new();
    // (slave node index, master labels, weights, record) resolved once all nodes are known.
    type SlaveSpec = (usize, Vec<i64>, Option<Vec<f64>>, Record);
    let mut slave_masters: Vec<SlaveSpec> = Vec::new();
    for i in 0..ndofman {
        let r = c.next_of(Block::Node, i, ndofman)?;
        let kw = r.keyword().to_string();
        if kw != "node" && kw != "slavenode" {
            return Err(r.error(format!(
                "expected node record {} of {ndofman} (Node or SlaveNode), found `{kw}`",
                i + 1
            )));
        }
        let label = r.number()?;
        let coords = r.float_array("coords")?;
        if coords.is_empty() || coords.len() > 3 {
            return Err(r.error(format!(
                "`coords` needs 1 to 3 values, found {}",
                coords.len()
            )));
        }
        for k in ["bc", "load", "lcs", "dofidmask"] {
            if r.flag(k) {
                return Err(r.error(format!(
                    "node keyword `{k}` is not supported; use sets and BC records"
                )));
            }
        }
        let mut x = [0.0; 3];
        x[..coords.len()].copy_from_slice(&coords);
        if node_index.insert(label, i).is_some() {
            return Err(r.error(format!("node label {label} is used twice")));
        }
        if kw == "slavenode" {
            let masters = r.int_array("masterdofman")?;
            let weights = r.opt_float_array("weights")?;
            r.opt_int_array("doftype")?;
            slave_masters.push((i, masters, weights, Record::new(r.line.clone())));
        }
        nodes.push(Node {
            label,
            coords: x,
            slave: None,
            span: r.span(),
        });
        c.finish(&r);
    }
    for (i, masters, weights, r) in slave_masters {
        if masters.is_empty() {
            return Err(r.error("`masterDofMan` lists no master node"));
        }
        let idx = masters
            .iter()
            .map(|&m| {
                node_index
                    .get(&(m as usize))
                    .copied()
                    .filter(|_| m > 0)
                    .ok_or_else(|| r.error(format!("master node {m} does not exist")))
            })
            .collect::<Result<Vec<_>>>()?;
        if idx.contains(&i) {
            return Err(r.error("a slave node cannot be its own master"));
        }
        let w = weights.unwrap_or_else(|| vec![1.0 / idx.len() as f64; idx.len()]);
        if w.len() != idx.len() {
            return Err(r.error(format!(
                "`weights` has {} values for {} master nodes",
                w.len(),
                idx.len()
            )));
        }
        nodes[i].slave = Some(SlaveLink {
            masters: idx,
            weights: w,
        });
    }
    for n in &nodes {
        if let Some(s) = &n.slave {
            if s.masters.iter().any(|&m| nodes[m].slave.is_some()) {
                return Err(Error::Input {
                    span: n.span.clone(),
                    msg: "a slave node's master must not itself be a slave node".into(),
                });
            }
        }
    }

    Ok((nodes, node_index))
}
