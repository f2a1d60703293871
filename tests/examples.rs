//! The examples of the documentation are tests: every command of a ```sh block of
//! README.md and of the pages in docs/ runs, in order, in one fresh folder, and exits 0.
//!
//! The rules the pages follow (docs/guarantees.md, "How it is tested"):
//! - A ```sh block holds only `seasynth` commands (with `\` continuations and trailing
//!   `# comments`) and comment lines; every one is run. Other shell (installing, `cargo`,
//!   `blender`, `parallel`, `sbatch`, `kubectl`) goes in ```bash blocks, synopses in
//!   ```text blocks: neither is run.
//! - The pages run in the order of [`PAGES`] (README first, each page after the pages it
//!   builds on), then any other page of docs/ by name; within a page, top to bottom. All run
//!   in one temporary folder that holds an empty `out/`, as the repository does, so an
//!   example may read what an earlier one wrote (`render --from out/sea.tif`) and names
//!   must not collide.
//! - A ```toml block whose first line is `# NAME.toml: …` is written as NAME.toml in the
//!   folder before its page's commands run (the manifest a `batch --manifest` reads).
//! - A pipe after a command (`… --plan | head -3`) is dropped: the command runs alone.
//! - Every path given to `-o`, `--plot`, `--plot2d` or `--plot-waves` exists afterwards
//!   (for `--tiles`, the first tile).
//! - The few examples too heavy for a test (a 32768² field, 480 frames) run with their size
//!   substituted by [`SUBSTITUTIONS`], each with its reason; an example is never edited to
//!   make it cheap. A substitution that no longer matches an example fails the test.

use std::path::{Path, PathBuf};
use std::time::Instant;

/// The pages, in the order their examples run.
const PAGES: &[&str] = &[
    "README.md",
    "docs/parameters.md",
    "docs/methods.md",
    "docs/formats.md",
    "docs/batches.md",
    "docs/clusters.md",
    "docs/render.md",
    "docs/guarantees.md",
    "docs/performance.md",
];

/// (page, text in the example, replacement, why).
const SUBSTITUTIONS: &[(&str, &str, &str, &str)] = &[
    (
        "README.md",
        "--frames 480",
        "--frames 4",
        "480 frames of a choppy 512² sea with normal and foam maps take minutes; 4 run the same code",
    ),
    (
        "README.md",
        "bench --sizes 1024 --repeats 3",
        "bench --sizes 64 --repeats 1",
        "the benchmark times every stage several times at 1024²; one run at 64² checks the command",
    ),
    (
        "docs/methods.md",
        "--size 32768 --extent 32768",
        "--size 512 --extent 512",
        "a 32768² TIFF is 4 GiB; a trochoid field written to a TIFF is streamed in strips at any size",
    ),
    (
        "docs/methods.md",
        "--frames 480",
        "--frames 4",
        "480 frames of a choppy 512² sea with normal and foam maps take minutes; 4 run the same code",
    ),
    (
        "docs/formats.md",
        "--size 4096 --tiles 4x4 -o out/x.obj",
        "--size 256 --tiles 4x4 -o out/x.obj",
        "4×4 OBJ tiles of a 4096² field are 3 GB of text; 256² gives the same 16 tiles",
    ),
    (
        "docs/formats.md",
        "--size 4096 --extent 4096 --engine unreal",
        "--size 512 --extent 512 --engine unreal",
        "the 4096² field takes seconds and 16 tiles of 1021²; 512² resamples and tiles the same way",
    ),
    (
        "docs/formats.md",
        "--frames 120",
        "--frames 3",
        "120 EXR frames of a choppy 512² sea take a minute; 3 run the same code",
    ),
    (
        "docs/clusters.md",
        "-o /shared/sea",
        "-o out/shared-sea",
        "the cluster's shared folder is a folder of the test's",
    ),
    (
        "docs/render.md",
        "--image 1920x1080 --spp 9",
        "--image 480x270 --spp 9",
        "a full-HD image at 9 rays per pixel takes seconds; a quarter of each side, the same rays",
    ),
];

/// One command of a page: its line, the command as written, and its words as run.
struct Example {
    page: String,
    line: usize,
    text: String,
    words: Vec<String>,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The pages in order: [`PAGES`], then every other page of docs/ by name.
fn pages() -> Vec<String> {
    let mut all: Vec<String> = PAGES.iter().map(|p| p.to_string()).collect();
    let mut rest: Vec<String> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .map(|e| format!("docs/{}", e.unwrap().file_name().to_string_lossy()))
        .filter(|p| p.ends_with(".md") && !all.contains(p))
        .collect();
    rest.sort();
    all.extend(rest);
    all
}

/// The fenced blocks of a page: (language, first line number, lines).
fn blocks(text: &str) -> Vec<(String, usize, Vec<String>)> {
    let mut out = Vec::new();
    let mut open: Option<(String, usize, Vec<String>)> = None;
    for (n, line) in text.lines().enumerate() {
        let fence = line.trim_start().strip_prefix("```");
        match (&mut open, fence) {
            (None, Some(lang)) => open = Some((lang.trim().to_string(), n + 2, Vec::new())),
            (Some(_), Some(_)) => out.push(open.take().expect("open block")),
            (Some((_, _, lines)), None) => lines.push(line.to_string()),
            (None, None) => {}
        }
    }
    out
}

/// A command line's words as a POSIX shell splits them (quotes, backslashes), up to an
/// unquoted `#` comment or `|` pipe.
fn shell_words(text: &str) -> Vec<String> {
    let mut words = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\'' => {
                in_word = true;
                for c in chars.by_ref() {
                    if c == '\'' {
                        break;
                    }
                    word.push(c);
                }
            }
            '"' => {
                in_word = true;
                while let Some(c) = chars.next() {
                    match c {
                        '"' => break,
                        '\\' if matches!(chars.peek(), Some('"' | '\\' | '$')) => {
                            word.push(chars.next().expect("peeked"))
                        }
                        c => word.push(c),
                    }
                }
            }
            '\\' => {
                in_word = true;
                if let Some(c) = chars.next() {
                    word.push(c);
                }
            }
            '#' if !in_word => break,
            '|' => break,
            c if c.is_whitespace() => {
                if in_word {
                    words.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            c => {
                in_word = true;
                word.push(c);
            }
        }
    }
    if in_word {
        words.push(word);
    }
    words
}

/// Every example of every page, substitutions applied, and the TOML files the pages
/// name; panics on a line of a ```sh block that is not a `seasynth` command.
fn examples(used: &mut [usize]) -> (Vec<Example>, Vec<(String, String)>) {
    let mut out = Vec::new();
    let mut files = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(root().join(&page)).expect("page");
        for (lang, first, lines) in blocks(&text) {
            if lang == "toml" {
                let name = lines
                    .first()
                    .and_then(|l| l.strip_prefix("# "))
                    .and_then(|l| l.split_once(": "))
                    .map(|(n, _)| n)
                    .filter(|n| n.ends_with(".toml") && !n.contains(['/', ' ']));
                if let Some(name) = name {
                    files.push((name.to_string(), lines.join("\n") + "\n"));
                }
                continue;
            }
            if lang != "sh" {
                continue;
            }
            let mut n = 0;
            while n < lines.len() {
                let line_no = first + n;
                let mut text = lines[n].trim().to_string();
                while text.ends_with('\\') && n + 1 < lines.len() {
                    text.pop();
                    n += 1;
                    text = format!("{} {}", text.trim_end(), lines[n].trim());
                }
                n += 1;
                if text.is_empty() || text.starts_with('#') {
                    continue;
                }
                assert!(
                    text.starts_with("seasynth "),
                    "{page}:{line_no}: a ```sh block holds only seasynth commands (put other \
                     shell in a ```bash block): {text}"
                );
                let mut run = text.clone();
                for (i, (p, from, to, _)) in SUBSTITUTIONS.iter().enumerate() {
                    if *p == page && run.contains(from) {
                        run = run.replacen(from, to, 1);
                        used[i] += 1;
                    }
                }
                let words = shell_words(&run);
                out.push(Example {
                    page: page.clone(),
                    line: line_no,
                    text,
                    words,
                });
            }
        }
    }
    (out, files)
}

/// The paths an example says it writes: its `-o`, `--plot`, `--plot2d`, `--plot-waves`
/// (the first tile with `--tiles`).
fn outputs(words: &[String]) -> Vec<PathBuf> {
    let tiled =
        words.iter().any(|w| w == "--tiles") && words.get(1).is_some_and(|c| c == "generate");
    let mut out = Vec::new();
    for pair in words.windows(2) {
        if ["-o", "--output", "--plot", "--plot2d", "--plot-waves"].contains(&pair[0].as_str()) {
            let p = PathBuf::from(&pair[1]);
            let is_tiled = tiled
                && p.extension().is_some_and(|e| {
                    ["obj", "glb", "r16", "r32"].contains(&e.to_str().unwrap_or(""))
                });
            out.push(match is_tiled {
                true => {
                    let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
                    let ext = p.extension().unwrap().to_string_lossy().into_owned();
                    p.with_file_name(format!("{stem}_x0_y0.{ext}"))
                }
                false => p,
            });
        }
    }
    out
}

#[test]
fn the_shell_words_are_split_as_a_shell_does() {
    assert_eq!(
        shell_words(r"seasynth batch --name 'pm-{a} b' --vary x=choice:a\|b -o out/x # c"),
        [
            "seasynth",
            "batch",
            "--name",
            "pm-{a} b",
            "--vary",
            "x=choice:a|b",
            "-o",
            "out/x"
        ]
    );
    assert_eq!(
        shell_words("seasynth batch --plan | head -3"),
        ["seasynth", "batch", "--plan"]
    );
    assert_eq!(shell_words(r#"a "b \"c\"" d#e"#), ["a", r#"b "c""#, "d#e"]);
}

#[test]
fn every_example_of_the_documentation_runs_in_order_in_a_fresh_folder() {
    let mut used = vec![0usize; SUBSTITUTIONS.len()];
    let (examples, files) = examples(&mut used);
    for (i, n) in used.iter().enumerate() {
        let (page, from, ..) = SUBSTITUTIONS[i];
        assert_eq!(
            *n, 1,
            "the substitution of `{from}` on {page} matches {n} examples, not 1"
        );
    }
    assert!(examples.len() >= 30, "{} examples", examples.len());
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("out")).unwrap();
    for (name, text) in &files {
        std::fs::write(d.join(name), text).unwrap();
    }
    let bin = env!("CARGO_BIN_EXE_seasynth");
    let started = Instant::now();
    let mut per_page: Vec<(String, usize, f64)> = Vec::new();
    for ex in &examples {
        let t = Instant::now();
        let out = std::process::Command::new(bin)
            .args(&ex.words[1..])
            .current_dir(d)
            .output()
            .expect("seasynth runs");
        let secs = t.elapsed().as_secs_f64();
        eprintln!(
            "{:6.2} s  {}:{}: {}",
            secs,
            ex.page,
            ex.line,
            ex.words.join(" ")
        );
        assert!(
            out.status.success(),
            "{}:{}: `{}` exited with {:?}:\n{}",
            ex.page,
            ex.line,
            ex.text,
            out.status.code(),
            String::from_utf8_lossy(&out.stderr)
        );
        for p in outputs(&ex.words) {
            assert!(
                Path::new(d).join(&p).exists(),
                "{}:{}: `{}` did not write {}",
                ex.page,
                ex.line,
                ex.text,
                p.display()
            );
        }
        match per_page.last_mut() {
            Some((page, n, s)) if *page == ex.page => {
                *n += 1;
                *s += secs;
            }
            _ => per_page.push((ex.page.clone(), 1, secs)),
        }
    }
    for (page, n, s) in &per_page {
        eprintln!("{page}: {n} examples, {s:.1} s");
    }
    eprintln!(
        "{} examples in {:.1} s",
        examples.len(),
        started.elapsed().as_secs_f64()
    );
}
