//! Cluster jobs for a sweep: one self-contained shell command per point
//! (`wasp sweep FILE --out DIR --point N -q`), safely quoted, and the
//! instructions printed with them (docs/sweep.md, "On a cluster").

use std::path::Path;

/// `s` as one shell word: unchanged when it holds only safe characters,
/// else in single quotes (a quote inside written `'\''`).
pub fn shell_quote(s: &str) -> String {
    let safe = |c: char| c.is_ascii_alphanumeric() || "_-./=:,+@%".contains(c);
    if !s.is_empty() && s.chars().all(safe) {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// The command line that started this process, quoted for a shell.
pub fn command_line() -> String {
    std::env::args()
        .enumerate()
        .map(|(i, a)| {
            if i == 0 {
                "wasp".to_string()
            } else {
                shell_quote(&a)
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The shell command that runs point `n` of the sweep `file` into `out`
/// with the `wasp` executable `exe` (all paths as given: pass absolute
/// ones).
pub fn job_line(exe: &Path, file: &Path, out: &Path, n: usize) -> String {
    let q = |p: &Path| shell_quote(&p.display().to_string());
    format!(
        "{} sweep {} --out {} --point {n} -q",
        q(exe),
        q(file),
        q(out)
    )
}

/// The jobs file: [`job_line`] for points 1 to `count`, one a line (line N
/// runs point N).
pub fn jobs_text(exe: &Path, file: &Path, out: &Path, count: usize) -> String {
    (1..=count)
        .map(|n| job_line(exe, file, out, n) + "\n")
        .collect()
}

/// What `--jobs-file` prints: the jobs file `jobs` of `count` points, how
/// to run it (GNU parallel, a Slurm array) and how to merge the results of
/// `out` afterwards (all paths absolute).
pub fn how_to_run(exe: &Path, file: &Path, out: &Path, jobs: &Path, count: usize) -> String {
    let q = |p: &Path| shell_quote(&p.display().to_string());
    let jq = q(jobs);
    let task = shell_quote(&format!("sed -n \"${{SLURM_ARRAY_TASK_ID}}p\" {jq} | sh"));
    format!(
        "wrote {jq}: {count} jobs, line N runs point N\n\
         run them, e.g. with GNU parallel:\n  \
         parallel -j 8 < {jq}\n\
         or as a Slurm array:\n  \
         sbatch --array=1-{count} --wrap {task}\n\
         then combine the results:\n  \
         {} merge {} --sweep {} --csv results.csv\n",
        q(exe),
        q(out),
        q(file)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shell_words_survive_spaces_quotes_and_dollars() {
        assert_eq!(shell_quote("/a/b-c_d.toml"), "/a/b-c_d.toml");
        assert_eq!(shell_quote("my dir"), "'my dir'");
        assert_eq!(shell_quote("it's"), "'it'\\''s'");
        assert_eq!(shell_quote("$HOME"), "'$HOME'");
        assert_eq!(shell_quote(""), "''");
        let line = job_line(
            Path::new("/bin/wasp"),
            Path::new("/s/my sweep.toml"),
            Path::new("/o"),
            7,
        );
        assert_eq!(
            line,
            "/bin/wasp sweep '/s/my sweep.toml' --out /o --point 7 -q"
        );
        let how = how_to_run(
            Path::new("/w"),
            Path::new("/f"),
            Path::new("/d"),
            Path::new("/j s"),
            3,
        );
        assert!(how.contains("\n  parallel -j 8 < '/j s'\n"), "{how}");
        assert!(
            how.contains(
                "\n  sbatch --array=1-3 --wrap 'sed -n \"${SLURM_ARRAY_TASK_ID}p\" '\\''/j s'\\'' | sh'\n"
            ),
            "{how}"
        );
        assert!(
            how.ends_with("\n  /w merge /d --sweep /f --csv results.csv\n"),
            "{how}"
        );
        let jobs = jobs_text(Path::new("/w"), Path::new("/f"), Path::new("/d"), 3);
        assert_eq!(jobs.lines().count(), 3);
        assert_eq!(
            jobs.lines().nth(2),
            Some("/w sweep /f --out /d --point 3 -q")
        );
    }
}
