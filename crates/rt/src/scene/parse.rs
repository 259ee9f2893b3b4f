//! Reading a scene file into a [`Scene`], with errors located at `file:line:column`.
//!
//! The document is parsed once into toml's spanned tree; serde reads the schema from a
//! copy of it, and the tree stays around to turn any error's path back into a place.

use super::Scene;
use super::schema::File;
use super::validate;
use serde::Deserialize;
use std::fmt;
use std::ops::Range;
use std::path::Path;
use toml::de::{DeTable, DeValue, Deserializer};

/// A problem with a scene file: `{origin}:{line}:{column}: {message}` when its place is
/// known, else `{origin}: {message}`.
#[derive(Debug, thiserror::Error)]
pub struct SceneError {
    origin: String,
    line_col: Option<(usize, usize)>,
    message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line_col {
            Some((line, column)) => write!(f, "{}:{line}:{column}: {}", self.origin, self.message),
            None => write!(f, "{}: {}", self.origin, self.message),
        }
    }
}

impl SceneError {
    /// 1-based.
    pub fn line(&self) -> Option<usize> {
        self.line_col.map(|(line, _)| line)
    }

    /// 1-based, in characters.
    pub fn column(&self) -> Option<usize> {
        self.line_col.map(|(_, column)| column)
    }

    /// The message without its place.
    pub fn message(&self) -> &str {
        &self.message
    }
}

/// Reads and parses a scene file; asset paths resolve against its folder.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let origin = path.display().to_string();
    match crate::files::read_to_string(path) {
        Ok(text) => parse(&text, &origin, path.parent().unwrap_or(Path::new(""))),
        Err(e) => Err(located(&origin, "", None, e.message())),
    }
}

/// Parses and validates scene text; `origin` names it in errors, and asset paths
/// resolve against `base_dir`.
pub fn parse(text: &str, origin: &str, base_dir: &Path) -> Result<Scene, SceneError> {
    let syntax = |e: toml::de::Error| located(origin, text, e.span(), e.message().to_owned());
    let root = DeTable::parse(text).map_err(syntax)?;
    let file = File::deserialize(Deserializer::from(root));
    let src = Source { origin, text, root: std::cell::OnceCell::new() };
    let file = file.map_err(|e| src.serde_error(&e))?;
    validate::scene(file, &src, base_dir)
}

/// One step of a path into the document.
#[derive(Clone, Copy)]
pub(super) enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

/// The text and its spanned tree, to place errors found after deserializing. The tree is
/// parsed again only when an error needs it: a scene of 100,000 spheres holds one tree
/// at a time, not two.
pub(super) struct Source<'t> {
    pub origin: &'t str,
    text: &'t str,
    root: std::cell::OnceCell<DeValue<'t>>,
}

impl<'t> Source<'t> {
    fn root(&self) -> &DeValue<'t> {
        self.root.get_or_init(|| match DeTable::parse(self.text) {
            Ok(root) => DeValue::Table(root.into_inner()),
            // The text parsed once already; an empty tree places the error at the top.
            Err(_) => DeValue::Table(Default::default()),
        })
    }

    /// An error about `field` of the item at `base`, placed at the deepest part of that
    /// path present in the file (the field may have been left to its default).
    pub fn error(&self, base: &[Seg], field: &str, message: impl fmt::Display) -> SceneError {
        let path = [base, &[Seg::Key(field)]].concat();
        let (item, field) = describe(&path);
        self.at(self.locate(&path), format!("{item}: {field} {message}"))
    }

    pub fn finite(&self, base: &[Seg], field: &str, values: &[f32]) -> Result<(), SceneError> {
        self.check(base, field, values, "", |_| true)
    }

    /// Rejects NaN, infinities, and any of `values` for which `ok` is false.
    pub fn check(
        &self,
        base: &[Seg],
        field: &str,
        values: &[f32],
        what: &str,
        ok: impl Fn(f32) -> bool,
    ) -> Result<(), SceneError> {
        match values.iter().find(|v| !v.is_finite() || !ok(**v)) {
            Some(v) if !v.is_finite() => Err(self.error(base, field, format!("must be finite, got {v}"))),
            // 1e20, not 100000000000000000000.
            Some(v) if v.abs() >= 1e7 => Err(self.error(base, field, format!("must be {what}, got {v:e}"))),
            Some(v) => Err(self.error(base, field, format!("must be {what}, got {v}"))),
            None => Ok(()),
        }
    }

    /// Where the item at `path` starts in the text, or its nearest present ancestor.
    pub fn locate(&self, path: &[Seg]) -> Option<Range<usize>> {
        let (mut node, mut span) = (self.root(), None);
        for seg in path {
            let Some(next) = (match *seg {
                Seg::Key(key) => node.get(key),
                Seg::Index(i) => node.get(i),
            }) else {
                break;
            };
            (node, span) = (next.get_ref(), Some(next.span()));
        }
        span
    }

    fn at(&self, span: Option<Range<usize>>, message: String) -> SceneError {
        located(self.origin, self.text, span, message)
    }

    /// Rewords serde's messages in the file's terms and adds a "did you mean".
    fn serde_error(&self, e: &toml::de::Error) -> SceneError {
        let mut path = Vec::new();
        if let Some(span) = e.span() {
            find(self.root(), &span, &mut path);
        }
        let (item, field) = describe(&path);
        let msg = e.message();
        // serde quotes the offending name first, then the expected ones, in backticks.
        let quoted: Vec<&str> = msg.split('`').skip(1).step_by(2).collect();
        let message = match quoted.split_first() {
            Some((name, known)) if msg.starts_with("unknown field") => {
                format!("unknown key `{name}` in {item}{}", hint(name, known.iter().copied()))
            }
            Some((name, known)) if msg.starts_with("unknown variant") => {
                format!("{item}: unknown {field} `{name}`{}", hint(name, known.iter().copied()))
            }
            _ if field.is_empty() => format!("{item}: {msg}"),
            _ => format!("{item}: {field}: {msg}"),
        };
        self.at(e.span(), message)
    }
}

/// Depth-first search for the key or value with exactly this span; leaves its path.
fn find<'a>(node: &'a DeValue<'_>, span: &Range<usize>, path: &mut Vec<Seg<'a>>) -> bool {
    let mut visit = |seg, key_span: Option<Range<usize>>, child: &'a toml::Spanned<DeValue<'_>>| {
        path.push(seg);
        // Deepest first: a lone [[mesh]] table shares its span with the array.
        let hit = find(child.get_ref(), span, path) || key_span.as_ref() == Some(span) || child.span() == *span;
        if !hit {
            path.pop();
        }
        hit
    };
    match node {
        DeValue::Table(t) => t.iter().any(|(k, v)| visit(Seg::Key(k.get_ref()), Some(k.span()), v)),
        DeValue::Array(a) => a.iter().enumerate().any(|(i, v)| visit(Seg::Index(i), None, v)),
        _ => false,
    }
}

/// Splits a path into the item a reader knows (`[sky]`, `sphere 2`) and the field in it.
fn describe(path: &[Seg]) -> (String, String) {
    use Seg::{Index, Key};
    let (item, rest) = match path {
        [Key(s @ ("render" | "camera" | "sky" | "sun")), rest @ ..] => (format!("[{s}]"), rest),
        [Key("materials"), Key(name), rest @ ..] => (format!("[materials.{name}]"), rest),
        [Key(s @ ("mesh" | "sphere" | "light" | "instances")), Index(i), rest @ ..] => (format!("{s} {}", i + 1), rest),
        _ => ("the top-level table".to_owned(), path),
    };
    let mut field = String::new();
    for seg in rest {
        match seg {
            Key(k) if field.is_empty() => field.push_str(k),
            Key(k) => field.push_str(&format!(".{k}")),
            Index(i) => field.push_str(&format!("[{i}]")),
        }
    }
    (item, field)
}

/// "; did you mean `x`?" when a candidate is close, else the list of candidates.
pub fn hint<'c>(name: &str, candidates: impl Iterator<Item = &'c str>) -> String {
    let candidates: Vec<&str> = candidates.collect();
    let near = |c: &str| 2.max(name.chars().count().max(c.chars().count()) / 3);
    match candidates.iter().min_by_key(|c| levenshtein(name, c)) {
        Some(best) if levenshtein(name, best) <= near(best) => format!("; did you mean `{best}`?"),
        Some(_) => format!("; expected one of `{}`", candidates.join("`, `")),
        None => String::new(),
    }
}

fn levenshtein(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let best = (diagonal + usize::from(ca != cb)).min(row[j] + 1).min(row[j + 1] + 1);
            diagonal = row[j + 1];
            row[j + 1] = best;
        }
    }
    row[b.len()]
}

/// Places an error at the 1-based line and column (in characters) where `span` starts.
fn located(origin: &str, text: &str, span: Option<Range<usize>>, message: String) -> SceneError {
    let line_col = span.map(|s| {
        let before = text.get(..s.start).unwrap_or(text);
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = before[line_start..].chars().count() + 1;
        (before.matches('\n').count() + 1, column)
    });
    let origin = origin.to_owned();
    SceneError { origin, line_col, message }
}
