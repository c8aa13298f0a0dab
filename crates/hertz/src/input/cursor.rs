//! Walking the records of an input file: the next record of a block (a record of another block
//! means a count is wrong), numbered records each once, unread tokens warned of.

use super::keywords::{is_condition, FUNCTION_KEYWORDS, MATERIAL_KEYWORDS};
use super::lexer::Line;
use super::record::Record;
use crate::error::{Error, Result};
use crate::model::*;

pub(super) struct Cursor<'w> {
    pub(super) lines: Vec<Line>,
    pub(super) pos: usize,
    pub(super) file: String,
    /// The caller's: the warnings met so far stay with it when reading fails.
    pub(super) warnings: &'w mut Vec<String>,
    /// The sets came right after the elements: a set record met later is one too many.
    pub(super) sets_read_early: bool,
}

impl Cursor<'_> {
    pub(super) fn next(&mut self, what: &str) -> Result<Record> {
        let Some(line) = self.lines.get(self.pos).cloned() else {
            return Err(Error::InputFile {
                file: self.file.clone(),
                msg: format!("unexpected end of file: expected {what}"),
            });
        };
        self.pos += 1;
        Ok(Record::new(line))
    }

    pub(super) fn peek_keyword(&self) -> Option<String> {
        self.lines.get(self.pos).map(|l| {
            Record::new(l.clone())
                .tokens
                .first()
                .cloned()
                .unwrap_or_default()
        })
    }

    /// Warn about tokens no lookup consumed (misspelled optional keywords).
    pub(super) fn finish(&mut self, r: &Record) {
        const SHOWN: usize = 6;
        let unread = r.unread();
        if !unread.is_empty() {
            let more = match unread.len().saturating_sub(SHOWN) {
                0 => String::new(),
                n => format!(" and {n} more"),
            };
            self.warnings.push(format!(
                "{}:{}: unread token(s) `{}`{more} in record `{}` (misspelled keyword, or an \
                 array longer than its count?)",
                r.line.file.display(),
                r.line.line,
                unread[..unread.len().min(SHOWN)].join(" "),
                r.keyword()
            ));
        }
    }
}

/// The record blocks of an input file, in file order (sets may also follow the elements).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
pub(super) enum Block {
    Node,
    Element,
    Segment,
    ContactSurface,
    CrossSection,
    Material,
    Condition,
    InitialCondition,
    TimeFunction,
    Set,
}

impl Block {
    /// The block a record keyword belongs to, if hertz knows the keyword.
    pub(super) fn of(kw: &str) -> Option<Block> {
        Some(match kw {
            "node" | "slavenode" => Block::Node,
            "simplecs" | "dummycs" => Block::CrossSection,
            "structuralfecontactsurface" => Block::ContactSurface,
            "dummymat" => Block::Material,
            "set" => Block::Set,
            "initialcondition" => Block::InitialCondition,
            _ if ElementType::from_keyword(kw).is_some()
                || super::upstream::CONTACT_ELEMENTS.iter().any(|c| c.0 == kw) =>
            {
                Block::Element
            }
            _ if super::contact::SEGMENTS.contains(&kw) => Block::Segment,
            _ if MATERIAL_KEYWORDS.contains(&kw) => Block::Material,
            _ if is_condition(kw) => Block::Condition,
            _ if FUNCTION_KEYWORDS.contains(&kw) => Block::TimeFunction,
            _ => return None,
        })
    }

    pub(super) fn name(self) -> &'static str {
        match self {
            Block::Node => "node",
            Block::Element => "element",
            Block::Segment => "contact segment",
            Block::ContactSurface => "contact surface",
            Block::CrossSection => "cross-section",
            Block::Material => "material",
            Block::Condition => "boundary-condition",
            Block::InitialCondition => "initial-condition",
            Block::TimeFunction => "time-function",
            Block::Set => "set",
        }
    }

    pub(super) fn count_key(self) -> &'static str {
        match self {
            Block::Node => "ndofman",
            Block::Element => "nelem",
            Block::Segment => "ncontactseg",
            Block::ContactSurface => "ncontactsurf",
            Block::CrossSection => "ncrosssect",
            Block::Material => "nmat",
            Block::Condition => "nbc",
            Block::InitialCondition => "nic",
            Block::TimeFunction => "nltf",
            Block::Set => "nset",
        }
    }
}

impl Cursor<'_> {
    /// Record `i` (0-based) of the `n` records of `block`. A record that belongs to another block
    /// means a count is wrong: the error names the count and the record found.
    pub(super) fn next_of(&mut self, block: Block, i: usize, n: usize) -> Result<Record> {
        let (name, key) = (block.name(), block.count_key());
        let r = self.next(&format!("{name} record {} of {n} (`{key} {n}`)", i + 1))?;
        let kw = r.keyword().to_string();
        match Block::of(&kw) {
            Some(found) if found != block => {
                let early_set = found == Block::Set && self.sets_read_early;
                let why = if found > block && !early_set {
                    format!("`{key} {n}` is larger than the {i} {name} record(s) present")
                } else {
                    format!("is `{}` too small?", found.count_key())
                };
                let other = found.name();
                let article = if other.starts_with(['a', 'e', 'i', 'o', 'u']) {
                    "an"
                } else {
                    "a"
                };
                Err(r.error(format!(
                    "expected {name} record {} of {n}, found `{kw}`, {article} {other} record: {why}",
                    i + 1
                )))
            }
            _ => Ok(r),
        }
    }
}

/// Numbered records (materials, sets, ...) must be numbered 1..=count, each once.
pub(super) struct Numbered<T> {
    pub(super) what: &'static str,
    pub(super) items: Vec<Option<T>>,
}

impl<T> Numbered<T> {
    pub(super) fn new(what: &'static str, count: usize) -> Self {
        Numbered {
            what,
            items: (0..count).map(|_| None).collect(),
        }
    }
    pub(super) fn put(&mut self, r: &Record, value: T) -> Result<()> {
        let n = r.number()?;
        let count = self.items.len();
        let slot = self.items.get_mut(n - 1).ok_or_else(|| {
            r.error(format!(
                "{} number {n} is out of range 1..{count} (the counts record declares {count})",
                self.what
            ))
        })?;
        if slot.is_some() {
            return Err(r.error(format!("{} number {n} is defined twice", self.what)));
        }
        *slot = Some(value);
        Ok(())
    }
    pub(super) fn finish(self) -> Vec<T> {
        self.items
            .into_iter()
            .map(|x| x.expect("all slots filled: count records read"))
            .collect()
    }
}

pub(super) fn check_ref(r: &Record, what: &str, n: Option<usize>, count: usize) -> Result<()> {
    match n {
        Some(v) if v == 0 || v > count => Err(r.error(format!(
            "{what} {v} does not exist (the counts record declares {count})"
        ))),
        _ => Ok(()),
    }
}
