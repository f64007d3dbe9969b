//! The validation report page `index.html`: the acceptance table, the run times of the
//! sections, every figure of every section, machine and version, and the command that
//! reproduces it.
//!
//! Plain HTML and CSS (no script, no external resource), so that it opens from disk, offline,
//! in any browser, and can be archived with the run's data files next to it.

use std::fmt::Write as _;
use std::fs;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use slender_validation::cantilever::Check;

use super::checks::format_measured;
use super::Section;
use crate::output::write_atomic;
use crate::store::record::CODE_VERSION;

/// Everything the page shows besides the files it finds.
pub struct Report<'a> {
    /// Acceptance targets.
    pub checks: &'a [Check],
    /// Benchmarks in order.
    pub sections: Vec<Section>,
    /// `quick` or `full`.
    pub preset: &'a str,
    /// Worker threads.
    pub jobs: usize,
    /// Wall time of the whole run (s).
    pub wall_seconds: f64,
}

/// Escapes text for HTML.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Quotes one argument for a POSIX shell when it needs it.
fn shell_quote(a: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "-_./=:,@%+".contains(c);
    if !a.is_empty() && a.chars().all(safe) {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', r"'\''"))
    }
}

/// The command line of this process, quoted for a shell.
pub fn command_line() -> String {
    let mut args = std::env::args();
    let _ = args.next();
    let rest: Vec<String> = args.map(|a| shell_quote(&a)).collect();
    format!("slender {}", rest.join(" "))
}

/// PNG figures of `dir`, sorted.
fn figures(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = fs::read_dir(dir)
        .map(|it| {
            it.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "png"))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// Data files (CSV, JSON) of `dir`, sorted.
fn data_files(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .map(|it| {
            it.flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "csv" || x == "json"))
                .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// A line of /proc-style `key: value` text.
fn proc_field(path: &str, key: &str) -> Option<String> {
    let text = fs::read_to_string(path).ok()?;
    text.lines()
        .find(|l| l.starts_with(key))
        .and_then(|l| l.split_once(':'))
        .map(|(_, v)| v.trim().to_string())
}

/// Machine facts as (label, value) rows.
fn machine() -> Vec<(&'static str, String)> {
    let unknown = || "unknown".to_string();
    let os = fs::read_to_string("/etc/os-release")
        .ok()
        .and_then(|t| {
            t.lines().find_map(|l| {
                l.strip_prefix("PRETTY_NAME=")
                    .map(|v| v.trim_matches('"').to_string())
            })
        })
        .unwrap_or_else(|| std::env::consts::OS.to_string());
    vec![
        (
            "host",
            fs::read_to_string("/proc/sys/kernel/hostname")
                .map(|s| s.trim().to_string())
                .unwrap_or_else(|_| unknown()),
        ),
        ("os", format!("{os} ({})", std::env::consts::ARCH)),
        (
            "cpu",
            proc_field("/proc/cpuinfo", "model name").unwrap_or_else(unknown),
        ),
        (
            "logical cores",
            std::thread::available_parallelism()
                .map(|n| n.to_string())
                .unwrap_or_else(|_| unknown()),
        ),
        (
            "memory",
            proc_field("/proc/meminfo", "MemTotal").unwrap_or_else(unknown),
        ),
    ]
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;max-width:1200px;margin:2em auto;\
padding:0 1em;color:#222}h1{margin-bottom:.2em}table{border-collapse:collapse;margin:1em 0}\
td,th{border:1px solid #ccc;padding:.3em .6em;text-align:left;vertical-align:top}\
td.num{text-align:right;font-variant-numeric:tabular-nums}td.target{white-space:nowrap}.pass{color:#0a6e0a;font-weight:bold}\
.fail{color:#b00;font-weight:bold}.banner{padding:.6em 1em;border-radius:6px;margin:1em 0}\
.ok{background:#e6f4e6}.bad{background:#fbe6e6}figure{display:inline-block;width:46%;\
margin:1%;vertical-align:top}figure img{width:100%;border:1px solid #ddd}\
figcaption{font-size:.9em;color:#444}code,pre{background:#f4f4f4;padding:.2em .4em}";

/// Writes `out/index.html`.
pub fn write_report(out: &Path, r: &Report) -> Result<PathBuf> {
    let failed = r.checks.iter().filter(|c| !c.passed).count();
    let mut h = String::new();
    let w = &mut h;
    let now = humantime::format_rfc3339_seconds(std::time::SystemTime::now());
    writeln!(
        w,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>slender validation report</title><style>{STYLE}</style></head><body>"
    )?;
    writeln!(w, "<h1>slender validation report</h1>")?;
    writeln!(
        w,
        "<p>Preset <b>{}</b>, {} worker thread(s), finished {now}, {:.1} s wall time.</p>",
        esc(r.preset),
        r.jobs,
        r.wall_seconds
    )?;
    writeln!(
        w,
        "<div class=\"banner {}\">{} of {} acceptance targets passed{}</div>",
        if failed == 0 { "ok" } else { "bad" },
        r.checks.len() - failed,
        r.checks.len(),
        if failed == 0 {
            String::new()
        } else {
            format!("; <span class=\"fail\">{failed} failed</span>")
        }
    )?;

    writeln!(w, "<h2>Acceptance targets</h2>\n<table><tr><th>result</th><th>benchmark</th><th>check</th><th>measured</th><th>target</th></tr>")?;
    for c in r.checks {
        writeln!(
            w,
            "<tr><td class=\"{}\">{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"target\">{}</td></tr>",
            if c.passed { "pass" } else { "fail" },
            if c.passed { "PASS" } else { "FAIL" },
            esc(&c.benchmark),
            esc(&c.description),
            format_measured(c.measured),
            esc(&c.target)
        )?;
    }
    writeln!(w, "</table><p>Also as <a href=\"checks.csv\">checks.csv</a> and <a href=\"checks.md\">checks.md</a>.</p>")?;

    writeln!(w, "<h2>Run times</h2>\n<table><tr><th>benchmark</th><th>wall time (s)</th><th>cases computed</th><th>cases reused from the store</th><th>Σ case time (s)</th></tr>")?;
    for s in &r.sections {
        writeln!(
            w,
            "<tr><td>{}</td><td class=\"num\">{:.1}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{:.1}</td></tr>",
            esc(&s.spec.title),
            s.tally.wall_seconds,
            s.tally.stats.computed,
            s.tally.stats.reused,
            s.tally.stats.case_seconds
        )?;
    }
    writeln!(w, "</table>")?;

    for s in &r.sections {
        let s = &s.spec;
        let dir = out.join(&s.dir);
        writeln!(
            w,
            "<h2 id=\"{}\">{}</h2>\n<p>{}</p>",
            esc(&s.dir),
            esc(&s.title),
            esc(&s.about)
        )?;
        let data = data_files(&dir);
        if !data.is_empty() {
            let links: Vec<String> = data
                .iter()
                .map(|f| format!("<a href=\"{0}/{1}\">{1}</a>", esc(&s.dir), esc(f)))
                .collect();
            writeln!(w, "<p>Data: {}</p>", links.join(", "))?;
        }
        for fig in figures(&dir) {
            let stem = fig
                .file_stem()
                .map(|x| x.to_string_lossy().into_owned())
                .unwrap_or_default();
            let png = format!("{}/{stem}.png", s.dir);
            let svg = format!("{}/{stem}.svg", s.dir);
            let target = if dir.join(format!("{stem}.svg")).exists() {
                svg
            } else {
                png.clone()
            };
            writeln!(
                w,
                "<figure><a href=\"{}\"><img src=\"{}\" alt=\"{}\"></a><figcaption>{}</figcaption></figure>",
                esc(&target),
                esc(&png),
                esc(&stem),
                esc(&(s.caption)(&stem))
            )?;
        }
    }

    writeln!(w, "<h2>Reproduce</h2>")?;
    writeln!(
        w,
        "<p>This run: <code>{}</code></p><p>From a checkout of the same code \
         (<code>{}</code>): <code>cargo run --release -- {}</code>. Finished cases are kept in \
         the result store and reused by a rerun; delete it to recompute everything.</p>",
        esc(&command_line()),
        esc(env!("SLENDER_GIT_COMMIT")),
        esc(command_line().trim_start_matches("slender "))
    )?;
    writeln!(w, "<h2>Version and machine</h2>\n<table>")?;
    let mut rows: Vec<(&str, String)> = vec![
        ("slender code version", CODE_VERSION.to_string()),
        (
            "git commit (at build)",
            env!("SLENDER_GIT_COMMIT").to_string(),
        ),
        ("compiler", env!("SLENDER_RUSTC_VERSION").to_string()),
    ];
    rows.extend(machine());
    for (k, v) in rows {
        writeln!(w, "<tr><th>{}</th><td>{}</td></tr>", esc(k), esc(&v))?;
    }
    writeln!(w, "</table>\n</body></html>")?;
    let path = out.join("index.html");
    write_atomic(&path, h.as_bytes()).with_context(|| format!("writing {}", path.display()))?;
    Ok(path)
}
