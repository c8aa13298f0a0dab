//! The `#%BEGIN_CHECK% … #%END_CHECK%` rules embedded in input files (spec §1.17), parsed from
//! the raw file with OOFEM's case-sensitive formats and evaluated after every step.

use crate::model::Model;
use crate::output::number::sci;
use crate::solve::StepResult;

/// What a rule checks.
#[derive(Debug, Clone, PartialEq)]
pub enum RuleKind {
    Node {
        node: usize,
        dof: u8,
        unknown: char,
    },
    Element {
        element: usize,
        irule: usize,
        gp: usize,
        keyword: usize,
        component: usize,
    },
    Reaction {
        node: usize,
        dof: u8,
    },
    LoadLevel,
    /// A rule line that matches no supported format; it fails with this reason.
    Unsupported(String),
}

#[derive(Debug, Clone)]
pub struct Rule {
    /// 1-based line in the input file.
    pub line: usize,
    pub text: String,
    pub step: usize,
    pub step_version: usize,
    pub kind: RuleKind,
    pub value: f64,
    pub tolerance: f64,
}

/// Outcome of evaluating one rule.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub rule: Rule,
    pub computed: Option<f64>,
    pub passed: bool,
    pub reason: Option<String>,
}

/// Parse the leading number of `s` like C `strtod` (0 if none).
fn strtod_prefix(s: &str) -> Option<f64> {
    let s = s.trim_start();
    let mut end = 0;
    let b = s.as_bytes();
    let mut best = None;
    while end < b.len() {
        end += 1;
        if let Some(v) = crate::input::record::parse_f64(&s[..end]) {
            best = Some(v);
        } else if !matches!(b[end - 1], b'e' | b'E' | b'+' | b'-' | b'.') {
            break;
        }
    }
    best
}

/// Match whitespace-separated tokens against a format: literal words, `%d`, `%f`, `%c`.
/// Returns the captured values and the number of tokens consumed.
fn scan(tokens: &[&str], fmt: &str) -> Option<(Vec<f64>, usize)> {
    let mut vals = Vec::new();
    let f: Vec<&str> = fmt.split_whitespace().collect();
    if tokens.len() < f.len() {
        return None;
    }
    for (t, p) in tokens.iter().zip(&f) {
        match *p {
            "%d" => vals.push(t.parse::<i64>().ok()? as f64),
            "%f" => vals.push(crate::input::record::parse_f64(t)?),
            "%c" => vals.push(t.chars().next()? as u32 as f64),
            lit => {
                if *t != lit {
                    return None;
                }
            }
        }
    }
    Some((vals, f.len()))
}

/// Extract the rules and the block tolerance from the raw input text.
pub fn parse_rules(raw: &str) -> (Vec<Rule>, Vec<String>) {
    let mut rules = Vec::new();
    let mut warnings = Vec::new();
    let mut inside = false;
    let mut tol = 1e-6;
    for (i, line) in raw.lines().enumerate() {
        let line = line.trim_end_matches('\r');
        if !inside {
            if line.starts_with("#%BEGIN_CHECK%") {
                inside = true;
                if line.len() >= 25 {
                    match strtod_prefix(line.get(25..).unwrap_or("")) {
                        Some(t) => tol = t,
                        None => {
                            warnings.push(format!(
                                "line {}: cannot read the block tolerance; using 0",
                                i + 1
                            ));
                            tol = 0.0;
                        }
                    }
                }
            }
            continue;
        }
        if line.starts_with("#%END_CHECK%") {
            break;
        }
        if line.len() < 3
            || !line.starts_with('#')
            || line.starts_with("##")
            || line.starts_with("#TIME")
        {
            continue;
        }
        rules.push(parse_rule(i + 1, line, tol));
    }
    (rules, warnings)
}

fn parse_rule(line: usize, text: &str, block_tol: f64) -> Rule {
    let toks: Vec<&str> = text.split_whitespace().collect();
    let mut rule = Rule {
        line,
        text: text.trim().to_string(),
        step: 0,
        step_version: 0,
        kind: RuleKind::Unsupported(String::new()),
        value: 0.0,
        tolerance: block_tol,
    };
    let head = toks[0];
    // "tStep s [tStepVer k]"
    let Some((v, mut pos)) = scan(&toks[1..], "tStep %d") else {
        rule.kind = RuleKind::Unsupported("cannot read `tStep`".into());
        rule.step = 1;
        return rule;
    };
    pos += 1;
    rule.step = v[0] as usize;
    if let Some((v, n)) = scan(&toks[pos..], "tStepVer %d") {
        rule.step_version = v[0] as usize;
        pos += n;
    }
    let rest = &toks[pos..];
    let parsed: Option<(RuleKind, f64, usize)> = match head {
        "#NODE" => scan(rest, "number %d dof %d unknown %c value %f").map(|(v, n)| {
            let kind = RuleKind::Node {
                node: v[0] as usize,
                dof: v[1] as u8,
                unknown: char::from_u32(v[2] as u32).unwrap_or('?'),
            };
            (kind, v[3], n)
        }),
        "#ELEMENT" => scan(
            rest,
            "number %d irule %d gp %d keyword %d component %d value %f",
        )
        .map(|(v, n)| (v, n, true))
        .or_else(|| {
            scan(rest, "number %d gp %d keyword %d component %d value %f")
                .map(|(v, n)| (v, n, false))
        })
        .map(|(v, n, with_irule)| {
            let o = usize::from(with_irule);
            let kind = RuleKind::Element {
                element: v[0] as usize,
                irule: if with_irule { v[1] as usize } else { 0 },
                gp: v[1 + o] as usize,
                keyword: v[2 + o] as usize,
                component: v[3 + o] as usize,
            };
            (kind, v[4 + o], n)
        }),
        "#REACTION" => scan(rest, "number %d dof %d value %f").map(|(v, n)| {
            (
                RuleKind::Reaction {
                    node: v[0] as usize,
                    dof: v[1] as u8,
                },
                v[2],
                n,
            )
        }),
        "#LOADLEVEL" => scan(rest, "value %f").map(|(v, n)| (RuleKind::LoadLevel, v[0], n)),
        other => {
            rule.kind = RuleKind::Unsupported(format!("rule type `{other}` is not supported"));
            return rule;
        }
    };
    match parsed {
        Some((kind, value, n)) => {
            rule.kind = kind;
            rule.value = value;
            if let Some((t, _)) = scan(&rest[n..], "tolerance %f") {
                rule.tolerance = t[0];
            }
        }
        None => rule.kind = RuleKind::Unsupported(format!("cannot parse `{head}` rule")),
    }
    rule
}

/// Evaluate the rules that apply to this step.
pub fn evaluate_step(model: &Model, rules: &[Rule], res: &StepResult) -> Vec<Outcome> {
    rules
        .iter()
        .filter(|r| r.step == res.step)
        .map(|r| {
            let computed = compute(model, r, res);
            match computed {
                Ok(v) => Outcome {
                    rule: r.clone(),
                    computed: Some(v),
                    passed: r.step_version == 0
                        && (r.value - r.tolerance..=r.value + r.tolerance).contains(&v),
                    reason: (r.step_version != 0)
                        .then(|| "step versions other than 0 do not exist".to_string()),
                },
                Err(reason) => Outcome {
                    rule: r.clone(),
                    computed: None,
                    passed: false,
                    reason: Some(reason),
                },
            }
        })
        .collect()
}

fn node_index(model: &Model, label: usize) -> Result<usize, String> {
    model
        .nodes
        .iter()
        .position(|n| n.label == label)
        .ok_or_else(|| format!("node {label} does not exist"))
}

fn compute(model: &Model, rule: &Rule, res: &StepResult) -> Result<f64, String> {
    match &rule.kind {
        RuleKind::Unsupported(why) => Err(why.clone()),
        RuleKind::LoadLevel => Ok(1.0),
        RuleKind::Node { node, dof, unknown } => {
            let n = node_index(model, *node)?;
            let code = res
                .dofs
                .code(n, *dof)
                .ok_or_else(|| format!("node {node} has no DOF {dof}"))?;
            let values = match (unknown, &res.motion) {
                ('d', _) => res.u,
                ('v', Some(m)) => m.velocity,
                ('a', Some(m)) => m.acceleration,
                ('v' | 'a', None) => {
                    return Err(format!(
                        "unknown `{unknown}`: a static analysis has displacements (d) only"
                    ))
                }
                _ => return Err(format!("unknown `{unknown}`: d, v or a")),
            };
            Ok(res.dofs.value(values, code))
        }
        RuleKind::Reaction { node, dof } => {
            let n = node_index(model, *node)?;
            res.dofs
                .prescribed
                .iter()
                .position(|&(pn, pd, _)| pn == n && pd == *dof)
                .map(|i| res.reactions[i])
                .ok_or_else(|| format!("DOF {dof} of node {node} is not prescribed: no reaction"))
        }
        RuleKind::Element {
            element,
            irule,
            gp,
            keyword,
            component,
        } => {
            let e = model
                .elements
                .iter()
                .position(|el| el.label == *element)
                .ok_or_else(|| format!("element {element} does not exist"))?;
            if *irule != 0 {
                return Err(format!("element {element} has only integration rule 0"));
            }
            let states = &res.states[e];
            let st = gp
                .checked_sub(1)
                .and_then(|g| states.get(g))
                .ok_or_else(|| {
                    format!(
                        "element {element} has integration points 1..{}",
                        states.len()
                    )
                })?;
            let plastic = match (keyword, st.plastic) {
                (13 | 27 | 31 | 52, None) => {
                    return Err(format!(
                        "element {element} has no plastic state (internal state type {keyword})"
                    ))
                }
                (_, p) => p.unwrap_or_default(),
            };
            let vec6 = match keyword {
                1 => st.stress,
                4 => st.strain,
                // OOFEM's internal states of MisesMat: 27 the plastic strain, 31 κ (its
                // IST_MaxEquivalentStrainLevel), 13 and 52 the damage.
                27 => plastic.strain,
                31 => [plastic.kappa, 0.0, 0.0, 0.0, 0.0, 0.0],
                13 | 52 => [plastic.damage, 0.0, 0.0, 0.0, 0.0, 0.0],
                81 => {
                    let s = st.stress;
                    let vm = (0.5
                        * ((s[0] - s[1]).powi(2) + (s[1] - s[2]).powi(2) + (s[2] - s[0]).powi(2))
                        + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]))
                        .sqrt();
                    [vm, 0.0, 0.0, 0.0, 0.0, 0.0]
                }
                k => {
                    return Err(format!(
                    "internal state type {k} is not supported (1 stress, 4 strain, 13 or 52 damage, 27 \
                     plastic strain, 31 equivalent plastic strain, 81 von Mises)"
                ))
                }
            };
            let n = if matches!(keyword, 13 | 31 | 52 | 81) {
                1
            } else {
                6
            };
            component
                .checked_sub(1)
                .filter(|&c| c < n)
                .map(|c| vec6[c])
                .ok_or_else(|| format!("component {component} out of range 1..{n}"))
        }
    }
}

/// One line describing a failed rule.
pub fn describe_failure(o: &Outcome) -> String {
    match (&o.computed, &o.reason) {
        (Some(v), None) => format!(
            "FAILED line {}: {}\n    computed {}, expected {} ± {}",
            o.rule.line,
            o.rule.text,
            sci(*v, 10),
            sci(o.rule.value, 10),
            sci(o.rule.tolerance, 1)
        ),
        (_, Some(r)) => format!("FAILED line {}: {}\n    {r}", o.rule.line, o.rule.text),
        (None, None) => format!("FAILED line {}: {}", o.rule.line, o.rule.text),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_parse_with_block_and_rule_tolerances() {
        let raw = "x\n#%BEGIN_CHECK% tolerance 1.e-4\n## comment\n#NODE tStep 1 number 3 dof 1 unknown d value -1.04\n\
                   #ELEMENT tStep 2 number 1 gp 4 keyword 1 component 6  value 0.0 tolerance 1e-2\n\
                   #ELEMENT tStep 1 number 1 irule 0 gp 2 keyword 4 component 1 value 5\n\
                   #REACTION tStep 1 number 8 dof 2 value -1.40625\n#%END_CHECK%\n#NODE tStep 1 number 1 dof 1 unknown d value 9\n";
        let (rules, w) = parse_rules(raw);
        assert!(w.is_empty());
        assert_eq!(rules.len(), 4);
        assert_eq!(
            rules[0].kind,
            RuleKind::Node {
                node: 3,
                dof: 1,
                unknown: 'd'
            }
        );
        assert_eq!(rules[0].tolerance, 1e-4);
        assert_eq!(
            rules[1].kind,
            RuleKind::Element {
                element: 1,
                irule: 0,
                gp: 4,
                keyword: 1,
                component: 6
            }
        );
        assert_eq!(rules[1].step, 2);
        assert_eq!(rules[1].tolerance, 1e-2);
        assert_eq!(
            rules[2].kind,
            RuleKind::Element {
                element: 1,
                irule: 0,
                gp: 2,
                keyword: 4,
                component: 1
            }
        );
        assert_eq!(rules[3].value, -1.40625);
    }

    #[test]
    fn lowercase_rule_keywords_do_not_match() {
        let (rules, _) = parse_rules(
            "#%BEGIN_CHECK%\n#NODE tstep 1 number 3 dof 1 unknown d value 1\n#%END_CHECK%\n",
        );
        assert!(matches!(rules[0].kind, RuleKind::Unsupported(_)));
    }
}
