//! README.md keeps its promises: every code block in it runs as written, and its links, and
//! those of the reference pages in docs/, lead somewhere.
//!
//! * ```` ```sh ````, ```` ```bash ```` and ```` ```console ```` blocks (in `console`, the lines
//!   after a `$ ` prompt): every line `ksmcmc ARGS` or `cargo run --release -- ARGS` runs with
//!   the built binary, in order, in a scratch folder: paths into the repository (`samples/...`)
//!   are read from the repository root, outputs go under `out/` (gitignored) in the scratch
//!   folder. Every `make TARGET` line names a target of the Makefile; they take minutes, so
//!   they are not run. Any other line fails: the test could not run it.
//!   The line `pip install ./python` is what `make test-python` runs, so it must be in the
//!   Makefile.
//! * The ```` ```html ```` block is the first ```` ```html ```` block of pkg/README.md byte for
//!   byte, which `tests/e2e/embed.test.mjs` runs in headless Chromium.
//! * The ```` ```python ```` block is the first ```` ```python ```` block of python/README.md
//!   byte for byte, which `python/tests/test_ksmcmc.py` runs (`make test-python`).
//! * A block in any other language fails, since nothing would run it.
//! * Links from README.md and docs/*.md to files (and `#anchors` of their headings) resolve,
//!   every docs page links back to the README, and the README links every docs page.

use std::collections::HashSet;
use std::path::Path;
use std::process::Command;

const RUN_PREFIXES: [&str; 2] = ["cargo run --release -- ", "ksmcmc "];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A fenced code block: its language, the line of its opening fence (from 1) and its text,
/// every line ending in a newline (what the e2e test's regex takes from pkg/README.md).
struct Block {
    lang: String,
    line: usize,
    lines: Vec<String>,
}

impl Block {
    fn text(&self) -> String {
        let mut text = String::new();
        for line in &self.lines {
            text.push_str(line);
            text.push('\n');
        }
        text
    }
}

/// The fenced blocks of a Markdown text, or why they cannot be read.
fn blocks(md: &str) -> Result<Vec<Block>, String> {
    let mut out = Vec::new();
    let mut open: Option<Block> = None;
    for (i, line) in md.lines().enumerate() {
        let fence = line.trim_start().starts_with("```");
        match open.take() {
            None if fence => {
                let lang = line.trim_start().trim_start_matches('`').trim().to_string();
                open = Some(Block { lang, line: i + 1, lines: Vec::new() });
            }
            None => {}
            Some(block) if fence && line.trim() == "```" => out.push(block),
            Some(mut block) => {
                block.lines.push(line.to_string());
                open = Some(block);
            }
        }
    }
    match open {
        Some(b) => Err(format!("the ```{} block at line {} is never closed", b.lang, b.line)),
        None => Ok(out),
    }
}

/// One command of the README to run: where it is, the line as written, and its arguments.
struct Run {
    line: usize,
    text: String,
    args: Vec<String>,
}

/// What the README's code blocks ask for, checked without running anything: the commands to
/// run, and the problems found (each naming the block and line).
fn plan(readme: &str, pkg_readme: &str, python_readme: &str, makefile: &str, repo: &Path) -> (Vec<Run>, Vec<String>) {
    let mut runs = Vec::new();
    let mut problems = Vec::new();
    let readme_blocks = match blocks(readme) {
        Ok(b) => b,
        Err(e) => return (runs, vec![format!("README.md: {e}")]),
    };
    let snippet = match blocks(pkg_readme) {
        Ok(b) => b.into_iter().find(|b| b.lang == "html").map(|b| b.text()),
        Err(e) => {
            problems.push(format!("pkg/README.md: {e}"));
            None
        }
    };
    let python_snippet = match blocks(python_readme) {
        Ok(b) => b.into_iter().find(|b| b.lang == "python").map(|b| b.text()),
        Err(e) => {
            problems.push(format!("python/README.md: {e}"));
            None
        }
    };
    let mut html_blocks = 0;
    let mut make_targets = HashSet::new();
    for block in &readme_blocks {
        let at = format!("README.md, the ```{} block at line {}", block.lang, block.line);
        match block.lang.as_str() {
            "sh" | "bash" | "console" => {}
            "html" => {
                html_blocks += 1;
                match &snippet {
                    None => problems.push(format!("{at}: pkg/README.md has no ```html block to compare it with")),
                    Some(s) if *s != block.text() => problems.push(format!(
                        "{at} is not the first ```html block of pkg/README.md (which tests/e2e/embed.test.mjs \
                         runs): copy that block here byte for byte"
                    )),
                    Some(_) => {}
                }
                continue;
            }
            "python" => {
                match &python_snippet {
                    None => problems.push(format!("{at}: python/README.md has no ```python block to compare it with")),
                    Some(s) if *s != block.text() => problems.push(format!(
                        "{at} is not the first ```python block of python/README.md (which \
                         python/tests/test_ksmcmc.py runs): copy that block here byte for byte"
                    )),
                    Some(_) => {}
                }
                continue;
            }
            other => {
                problems.push(format!(
                    "{at}: nothing runs a ```{other} block; use ```sh for commands (run by tests/it/readme.rs) \
                     or the ```html embed of pkg/README.md (run by tests/e2e/embed.test.mjs), or move it to docs/"
                ));
                continue;
            }
        }
        for (k, raw) in block.lines.iter().enumerate() {
            let line = block.line + 1 + k;
            let at = format!("README.md line {line} (the ```{} block at line {})", block.lang, block.line);
            let command = if block.lang == "console" {
                match raw.strip_prefix("$ ") {
                    Some(c) => c,
                    None => continue, // the command's output
                }
            } else {
                raw.as_str()
            };
            let command = strip_comment(command).trim();
            if command.is_empty() {
                continue;
            }
            if command == "pip install ./python" {
                if !makefile.lines().any(|l| l.contains("pip install") && l.contains(" ./python")) {
                    problems.push(format!("{at}: `{command}`: no Makefile recipe runs it (make test-python should)"));
                }
                continue;
            }
            if let Some(rest) = command.strip_prefix("make ") {
                let targets: Vec<&str> = rest.split_whitespace().filter(|w| !w.contains('=')).collect();
                if targets.is_empty() {
                    problems.push(format!("{at}: `{command}` names no target"));
                }
                for t in targets {
                    if makefile.lines().any(|l| l.starts_with(&format!("{t}:"))) {
                        make_targets.insert(t.to_string());
                    } else {
                        problems.push(format!("{at}: `{command}`: the Makefile has no target `{t}`"));
                    }
                }
                continue;
            }
            let Some(rest) = RUN_PREFIXES.iter().find_map(|p| command.strip_prefix(p)) else {
                problems.push(format!(
                    "{at}: `{command}` is neither `ksmcmc ARGS`, `cargo run --release -- ARGS` nor `make TARGET`, \
                     so the test cannot run it"
                ));
                continue;
            };
            if let Some(c) = rest.chars().find(|c| "'\"$|&;<>`*\\(){}".contains(*c)) {
                problems.push(format!("{at}: `{command}` uses shell syntax ({c}); write plain words the test can run"));
                continue;
            }
            let mut args: Vec<String> = rest.split_whitespace().map(String::from).collect();
            let mut ok = true;
            for (j, arg) in args.iter_mut().enumerate() {
                if arg.starts_with("--out=") {
                    problems.push(format!("{at}: write `--out DIR`, not `{arg}`"));
                    ok = false;
                } else if arg.starts_with('/') {
                    problems.push(format!(
                        "{at}: `{arg}` is an absolute path; name inputs from the repository root and write outputs under out/"
                    ));
                    ok = false;
                } else if is_output(arg) {
                    // made by this or an earlier line, in the scratch folder
                } else if j > 0 && rest.split_whitespace().nth(j - 1) == Some("--out") {
                    problems.push(format!("{at}: `--out {arg}` writes outside out/ (which git ignores)"));
                    ok = false;
                } else if arg.contains('/') && !arg.starts_with('-') {
                    let path = repo.join(arg.as_str());
                    if path.exists() {
                        *arg = path.to_string_lossy().into_owned();
                    } else {
                        problems.push(format!("{at}: `{arg}` is not in the repository"));
                        ok = false;
                    }
                }
            }
            if ok {
                runs.push(Run { line, text: command.to_string(), args });
            }
        }
    }
    if html_blocks == 0 {
        problems
            .push("README.md has no ```html block: the browser package's example (pkg/README.md's) is missing".into());
    }
    if runs.is_empty() {
        problems.push("README.md has no command line to run (`cargo run --release -- ...` in a ```sh block)".into());
    }
    for t in ["demo", "test"] {
        if !make_targets.contains(t) {
            problems.push(format!("README.md does not show `make {t}` in a ```sh block"));
        }
    }
    (runs, problems)
}

/// A path the README's commands write (or read back): under `out/`, in the scratch folder.
fn is_output(arg: &str) -> bool {
    arg == "out" || arg.starts_with("out/")
}

/// The line without a shell comment (`#` at its start or after a blank).
fn strip_comment(line: &str) -> &str {
    let mut prev = ' ';
    for (i, c) in line.char_indices() {
        if c == '#' && prev.is_whitespace() {
            return &line[..i];
        }
        prev = c;
    }
    line
}

/// GitHub's anchors for the headings of a Markdown text (outside code blocks).
fn anchors(md: &str) -> HashSet<String> {
    let mut seen = HashSet::new();
    let mut in_code = false;
    for line in md.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code || !line.starts_with('#') {
            continue;
        }
        let title = line.trim_start_matches('#');
        if !title.starts_with(' ') {
            continue;
        }
        let slug: String = title
            .trim()
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || *c == ' ' || *c == '-' || *c == '_')
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let mut anchor = slug.clone();
        let mut n = 0;
        while !seen.insert(anchor.clone()) {
            n += 1;
            anchor = format!("{slug}-{n}");
        }
    }
    seen
}

/// The Markdown text without its fenced code blocks (links there are code, not links).
fn prose(md: &str) -> String {
    let mut in_code = false;
    let mut out = String::new();
    for line in md.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
        } else if !in_code {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}

/// The targets of the links `[text](target)` in a Markdown text, with their lines.
fn links(md: &str) -> Vec<(usize, String)> {
    let text = prose(md);
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(i) = text[from..].find("](") {
        let start = from + i + 2;
        let Some(len) = text[start..].find(')') else { break };
        let line = text[..start].matches('\n').count() + 1;
        out.push((line, text[start..start + len].to_string()));
        from = start + len;
    }
    out
}

/// Links of `file` (relative to `repo`) that lead nowhere: a missing file or heading.
fn link_problems(repo: &Path, file: &str) -> Vec<String> {
    let md = read(&repo.join(file));
    let dir = repo.join(file).parent().unwrap().to_path_buf();
    let mut problems = Vec::new();
    for (line, target) in links(&md) {
        if target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        let (path, anchor) = match target.split_once('#') {
            Some((p, a)) => (p, Some(a)),
            None => (target.as_str(), None),
        };
        let linked = if path.is_empty() { repo.join(file) } else { dir.join(path) };
        if !linked.exists() {
            problems.push(format!("{file} line {line}: the link to `{target}`: {} does not exist", linked.display()));
            continue;
        }
        if let Some(anchor) = anchor {
            let is_md = linked.extension().is_some_and(|e| e == "md");
            if !is_md || !anchors(&read(&linked)).contains(anchor) {
                problems
                    .push(format!("{file} line {line}: the link to `{target}`: no heading has the anchor #{anchor}"));
            }
        }
    }
    problems
}

/// The docs pages, as `docs/NAME.md`.
fn docs_pages(repo: &Path) -> Vec<String> {
    let mut pages: Vec<String> = std::fs::read_dir(repo.join("docs"))
        .map(|d| d.filter_map(|e| e.ok()).map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default();
    pages.retain(|n| n.ends_with(".md"));
    pages.sort();
    pages.into_iter().map(|n| format!("docs/{n}")).collect()
}

/// The README's and the docs pages' links, and the links between them.
fn all_link_problems(repo: &Path) -> Vec<String> {
    let mut problems = link_problems(repo, "README.md");
    let readme_links: HashSet<String> = links(&read(&repo.join("README.md"))).into_iter().map(|(_, t)| t).collect();
    let pages = docs_pages(repo);
    if pages.is_empty() {
        problems.push("docs/ holds no reference page (docs/*.md)".into());
    }
    for page in pages {
        problems.extend(link_problems(repo, &page));
        if !links(&read(&repo.join(&page))).iter().any(|(_, t)| t == "../README.md") {
            problems.push(format!("{page} does not link back to the README ([README](../README.md))"));
        }
        if !readme_links.iter().any(|t| t.split('#').next() == Some(page.as_str())) {
            problems.push(format!("README.md does not link {page}"));
        }
    }
    problems
}

#[test]
fn readme_code_blocks_are_what_the_tests_run() {
    let repo = root();
    let (runs, problems) = plan(
        &read(&repo.join("README.md")),
        &read(&repo.join("pkg/README.md")),
        &read(&repo.join("python/README.md")),
        &read(&repo.join("Makefile")),
        repo,
    );
    assert!(problems.is_empty(), "README.md's code blocks:\n  {}", problems.join("\n  "));
    let scratch = crate::common::tmp_dir("readme", "commands");
    for run in &runs {
        let out = Command::new(env!("CARGO_BIN_EXE_ksmcmc")).args(&run.args).current_dir(&scratch).output().unwrap();
        let said = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        assert!(
            out.status.success() && !said.contains("panicked"),
            "README.md line {}: `{}` failed ({}) in {}:\n{said}",
            run.line,
            run.text,
            out.status,
            scratch.display()
        );
        if let Some(i) = run.args.iter().position(|a| a == "--out") {
            let made = scratch.join(&run.args[i + 1]);
            assert!(
                made.exists(),
                "README.md line {}: `{}` succeeded but wrote no {}",
                run.line,
                run.text,
                made.display()
            );
        }
    }
}

#[test]
fn readme_and_docs_links_resolve() {
    let problems = all_link_problems(root());
    assert!(problems.is_empty(), "links:\n  {}", problems.join("\n  "));
}

/// The checks above find what they are there to find.
#[test]
fn the_checks_catch_a_stale_readme() {
    let repo = root();
    let pkg = "x\n```html\n<p>hi</p>\n```\n";
    let makefile = "demo: pkg\n\tserve\ntest:\n\tcheck\n";
    let good =
        "```sh\nmake demo   # serve\nmake test\ncargo run --release -- info samples/office-small/map.yaml\n```\n\n\
                ```html\n<p>hi</p>\n```\n";
    let python = "y\n```python\nimport ksmcmc\n```\n";
    let (runs, problems) = plan(good, pkg, python, makefile, repo);
    assert!(problems.is_empty(), "{problems:?}");
    assert_eq!(runs.len(), 1);
    assert_eq!(runs[0].line, 4);
    assert_eq!(runs[0].args[0], "info");
    assert_eq!(Path::new(&runs[0].args[1]), repo.join("samples/office-small/map.yaml"));
    let cases: &[(&str, &str)] = &[
        ("```js\nmount()\n```\n", "nothing runs a ```js block"),
        ("```html\n<p>hello</p>\n```\n", "is not the first ```html block of pkg/README.md"),
        ("```python\nimport numpy\n```\n", "is not the first ```python block of python/README.md"),
        ("```sh\npip install ./python\n```\n", "no Makefile recipe runs it"),
        ("```sh\nmake demos\n```\n", "the Makefile has no target `demos`"),
        ("```sh\nnpm install ksmcmc\n```\n", "README.md line 2 (the ```sh block at line 1)"),
        ("```sh\nksmcmc floorplan samples/nowhere/map.yaml --out out/p\n```\n", "`samples/nowhere/map.yaml` is not in"),
        ("```sh\nksmcmc synth --seed 1 --out /tmp/x\n```\n", "absolute path"),
        ("```sh\nksmcmc synth --seed 1 --out samples/x\n```\n", "writes outside out/"),
        ("```sh\nksmcmc synth --seed $SEED --out out/x\n```\n", "shell syntax"),
        ("```console\n$ ksmcmc info samples/gone.pgm\nsome output\n```\n", "README.md line 2 (the ```console block"),
        ("```sh\nmake demo\n", "never closed"),
        ("no code at all\n", "no ```html block"),
        ("no code at all\n", "no command line to run"),
        ("no code at all\n", "does not show `make demo`"),
    ];
    for (readme, needle) in cases {
        let (_, problems) = plan(readme, pkg, python, makefile, repo);
        assert!(problems.iter().any(|p| p.contains(needle)), "{readme:?} should give {needle:?}, gave {problems:?}");
    }
    // Console output lines are not commands; comments are not arguments.
    let (runs, _) = plan("```console\n$ ksmcmc help   # all\nUsage: ...\n```\n", pkg, python, makefile, repo);
    assert_eq!(runs.len(), 1);
    assert_eq!(runs[0].args, ["help"]);

    // Links: a missing file, a missing heading, a docs page that does not link back.
    let dir = crate::common::tmp_dir("readme", "links");
    std::fs::create_dir_all(dir.join("docs")).unwrap();
    std::fs::write(
        dir.join("README.md"),
        "# Top\n\nSee [cli](docs/cli.md#the-commands), [gone](docs/gone.md),\n[bad](docs/cli.md#nowhere) and [self](#top).\n",
    )
    .unwrap();
    std::fs::write(dir.join("docs/cli.md"), "# CLI\n\n## The `commands`\n\nBack: [README](../README.md).\n").unwrap();
    std::fs::write(dir.join("docs/lost.md"), "# Lost\n\n```sh\n# [x](nowhere.md)\n```\n").unwrap();
    let problems = all_link_problems(&dir);
    let expect = [
        "README.md line 3: the link to `docs/gone.md`",
        "README.md line 4: the link to `docs/cli.md#nowhere`: no heading has the anchor #nowhere",
        "docs/lost.md does not link back to the README",
        "README.md does not link docs/lost.md",
    ];
    for needle in expect {
        assert!(problems.iter().any(|p| p.contains(needle)), "no {needle:?} in {problems:?}");
    }
    assert_eq!(problems.len(), expect.len(), "{problems:?}");
}
