//! The assembler's two directives: `//#if` blocks, applied to each file, and
//! `//#include` lines, followed from a program's entry file.

use super::ShaderFiles;
use std::collections::HashSet;

/// The module assembled from `entry` and what it includes, each file once and after
/// the files it includes, under the flags `flag` gives (`None`: an unknown flag).
pub(super) fn resolve(files: &ShaderFiles, entry: &str, flag: &dyn Fn(&str) -> Option<bool>) -> Result<String, String> {
    let text = files.read(entry)?;
    let mut resolver = Resolver { files, flag, open: Vec::new(), written: HashSet::new(), source: String::new() };
    resolver.write(entry, &text)?;
    Ok(resolver.source)
}

struct Resolver<'a> {
    files: &'a ShaderFiles,
    flag: &'a dyn Fn(&str) -> Option<bool>,
    /// The files whose includes are being followed, outermost first: including one
    /// of them again closes a cycle.
    open: Vec<String>,
    written: HashSet<String>,
    source: String,
}

impl Resolver<'_> {
    /// Writes the files that `name` includes (those not written yet), then `name`.
    fn write(&mut self, name: &str, text: &str) -> Result<(), String> {
        self.open.push(name.to_owned());
        let mut body = String::new();
        for (number, line) in kept_lines(name, text, self.flag)? {
            let Some(include) = include_of(line) else {
                body.push_str(line);
                body.push('\n');
                continue;
            };
            let at = format!("shaders/{name}:{number}");
            let included = include.map_err(|e| format!("{at}: {e}"))?;
            if let Some(first) = self.open.iter().position(|open| open == included) {
                let cycle = self.open[first..].join(" → ");
                return Err(format!("{at}: including {included} closes a cycle: {cycle} → {included}"));
            }
            if !self.written.contains(included) {
                let text = self.files.read(included).map_err(|e| format!("{at}: cannot include {included}: {e}"))?;
                self.write(included, &text)?;
            }
        }
        self.open.pop();
        self.written.insert(name.to_owned());
        self.source.push_str(&format!("// ---- shaders/{name}\n"));
        self.source.push_str(&body);
        Ok(())
    }
}

/// The file an `//#include "name.wgsl"` line names (`None`: not an include line).
pub(super) fn include_of(line: &str) -> Option<Result<&str, String>> {
    let rest = line.trim().strip_prefix("//#include")?;
    let name = rest.trim().strip_prefix('"').and_then(|r| r.strip_suffix('"'));
    Some(match name {
        Some(name) if !name.is_empty() && !name.contains(['"', '/', '\\']) => Ok(name),
        _ => Err(format!("expected `//#include \"file.wgsl\"` (a file of the same folder), found `{}`", line.trim())),
    })
}

/// The lines of `file` (numbered from 1) that its `//#if` directives keep; a mistake in
/// them (an unknown flag, unbalanced directives) is an error naming the file and line.
pub(super) fn kept_lines<'t>(
    file: &str,
    text: &'t str,
    flag: &dyn Fn(&str) -> Option<bool>,
) -> Result<Vec<(usize, &'t str)>, String> {
    let mut kept = Vec::new();
    // For each open `#if`: (its branch is taken, the enclosing lines are kept).
    let mut stack: Vec<(bool, bool)> = Vec::new();
    let keeping = |stack: &[(bool, bool)]| stack.last().is_none_or(|&(taken, outer)| taken && outer);
    for (n, line) in text.lines().enumerate() {
        let at = || format!("shaders/{file}:{}", n + 1);
        let directive = line.trim_start();
        if let Some(cond) = directive.strip_prefix("//#if ") {
            let cond = cond.trim();
            let (negated, name) = cond.strip_prefix('!').map_or((false, cond), |n| (true, n));
            let value = flag(name).ok_or_else(|| format!("{}: unknown flag `{name}`", at()))?;
            let outer = keeping(&stack);
            stack.push((value != negated, outer));
        } else if directive.starts_with("//#else") {
            let top = stack.last_mut().ok_or_else(|| format!("{}: #else without #if", at()))?;
            top.0 = !top.0;
        } else if directive.starts_with("//#endif") {
            stack.pop().ok_or_else(|| format!("{}: #endif without #if", at()))?;
        } else if keeping(&stack) {
            kept.push((n + 1, line));
        }
    }
    if !stack.is_empty() {
        return Err(format!("shaders/{file}: unclosed #if"));
    }
    Ok(kept)
}
