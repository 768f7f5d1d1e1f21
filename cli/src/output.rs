//! Writing result files so that a failure never leaves a half-written file behind: each file is
//! written beside its destination and renamed into place.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Checks, before a long run, that [`write_atomic`] will be able to write `path` (`flag`: the
/// argument that named it): its folder can be created and written to, and it is not a folder
/// itself. A run of hours whose `--csv` points into `/proc` or at a folder failed at its end.
pub fn check_writable(flag: &str, path: &Path) -> Result<(), String> {
    if path.is_dir() {
        return Err(format!(
            "{flag} {}: is a folder, not a file",
            path.display()
        ));
    }
    let probe = path.with_file_name(format!(".rocking-probe-{}", std::process::id()));
    write_atomic(&probe, b"").map_err(|e| format!("{flag}: {e}"))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Checks, before a run, that `path` (`flag`: the argument that named it) can be written, a
/// file, or with `folder` a folder to write into, without creating anything: a run that fails
/// leaves no empty folder behind. The nearest existing folder on its way must take a file.
pub fn check_creatable(flag: &str, path: &Path, folder: bool) -> Result<(), String> {
    if path.is_dir() != folder && path.exists() {
        let what = if folder {
            "a file, not a folder"
        } else {
            "a folder, not a file"
        };
        return Err(format!("{flag} {}: is {what}", path.display()));
    }
    let start = if folder && path.is_dir() {
        path
    } else {
        path.parent().unwrap_or(Path::new("."))
    };
    let mut dir = if start.as_os_str().is_empty() {
        Path::new(".")
    } else {
        start
    };
    while !dir.exists() {
        dir = match dir.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => Path::new("."),
        };
    }
    if !dir.is_dir() {
        return Err(format!(
            "{flag} {}: {} is a file, not a folder",
            path.display(),
            dir.display()
        ));
    }
    let probe = dir.join(format!(".rocking-probe-{}", std::process::id()));
    std::fs::write(&probe, b"").map_err(|e| {
        format!(
            "{flag} {}: cannot write in {}: {e}",
            path.display(),
            dir.display()
        )
    })?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Removes the `history.csv` and `events.jsonl` of an earlier run from `out` when this run
/// writes none (`output.history` / `output.events` false), after it succeeded: a folder with
/// an old run's events beside this run's summary contradicted itself.
pub fn remove_unwritten(out: &Path, output: &rocking::scene::OutputSpec) -> Result<(), String> {
    for (name, written) in [
        ("history.csv", output.history),
        ("events.jsonl", output.events),
    ] {
        let path = out.join(name);
        if written {
            continue;
        }
        match std::fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(format!("cannot remove the earlier {}: {e}", path.display()))
            }
            _ => {}
        }
    }
    Ok(())
}

/// Writes `bytes` to `path` atomically (temporary file in the same directory, then rename).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Writes what `write` puts out to `path` atomically, as [`write_atomic`], through a buffer: a
/// history of hundreds of megabytes goes to the file as it is formatted instead of being held
/// whole in memory first (a twenty-drum run at dt = 0.1 ms held a 420 MB string).
pub fn write_atomic_with<F>(path: &Path, write: F) -> Result<(), String>
where
    F: FnOnce(&mut BufWriter<File>) -> std::io::Result<()>,
{
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let name = path
        .file_name()
        .ok_or_else(|| format!("{} is not a file path", path.display()))?;
    let tmp = dir.join(format!(
        ".{}.partial-{}",
        name.to_string_lossy(),
        std::process::id()
    ));
    let written = File::create(&tmp).and_then(|file| {
        let mut w = BufWriter::with_capacity(1 << 16, file);
        write(&mut w)?;
        w.into_inner().map(drop).map_err(|e| e.into_error())
    });
    written.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("cannot write {}: {e}", path.display())
    })?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("cannot write {}: {e}", path.display())
    })
}

/// `value` as a JSON tree, its keys in alphabetical order (every JSON output of the CLI has them
/// so, as `tests/golden` holds them; serde_json's map is sorted without `preserve_order`). Floats
/// print as the shortest text that reads back to the same `f64` (ryu); NaN and infinities as
/// `null`.
pub fn json_tree(value: &impl serde::Serialize) -> Result<serde_json::Value, String> {
    serde_json::to_value(value).map_err(|e| e.to_string())
}

/// Prints `value` as pretty JSON on stdout ([`json_tree`]'s key order).
pub fn print_json(value: &impl serde::Serialize) -> Result<(), String> {
    println!(
        "{}",
        serde_json::to_string_pretty(&json_tree(value)?).map_err(|e| e.to_string())?
    );
    Ok(())
}

/// Reads a JSON file. serde_json is built with `float_roundtrip`: every number reads back as the
/// `f64` that was written (its default parser can land one ulp off, which made a merged shard
/// differ from the whole run).
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path) -> Result<T, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))
}

/// `prefix` followed by `suffix`: `with_suffix("out/ff", "-oas.svg")` is `out/ff-oas.svg` (a
/// prefix is a path and a file-name stem, not a folder).
pub fn with_suffix(prefix: &Path, suffix: &str) -> std::path::PathBuf {
    let mut s = prefix.as_os_str().to_owned();
    s.push(suffix);
    std::path::PathBuf::from(s)
}

#[cfg(test)]
mod tests {
    /// Numbers printed by serde_json read back bit for bit, including issue 10's β of LOS000
    /// (1.6338356152437565, which the default parser read as …563) and a spread of magnitudes.
    #[test]
    fn json_numbers_round_trip_exactly() {
        let mut xs = vec![1.6338356152437565, 3.4551072945922194, 242.44620170823282];
        let mut x = 0.1234567_f64;
        for _ in 0..20_000 {
            // A deterministic spread over magnitudes and mantissas.
            x = (x * 7.318_220_9 + 0.619_283).fract();
            xs.push(x * 10f64.powi((x * 40.0) as i32 - 20));
        }
        let text = serde_json::to_string(&xs).unwrap();
        let back: Vec<f64> = serde_json::from_str(&text).unwrap();
        for (a, b) in xs.iter().zip(&back) {
            assert_eq!(a.to_bits(), b.to_bits(), "{a} read back as {b}");
        }
    }

    /// A file written through [`super::write_atomic_with`] appears whole or not at all: a writer
    /// that fails half-way leaves neither the file nor its temporary beside it, and an earlier
    /// file of that name stays as it was.
    #[test]
    fn a_failed_write_leaves_nothing_half_written() {
        use std::io::Write;
        let dir = std::env::temp_dir().join(format!("rocking-atomic-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let path = dir.join("history.csv");
        super::write_atomic_with(&path, |w| {
            for i in 0..100_000 {
                writeln!(w, "{i},{}", i as f64 * 0.5)?;
            }
            Ok(())
        })
        .unwrap();
        let whole = std::fs::read_to_string(&path).unwrap();
        assert_eq!(whole.lines().count(), 100_000);
        assert!(whole.ends_with("99999,49999.5\n"));
        let failed = super::write_atomic_with(&path, |w| {
            w.write_all(&[b'x'; 200_000])?; // past the buffer: some of it reached the file
            Err(std::io::Error::other("disk full"))
        });
        let message = failed.unwrap_err();
        assert!(
            message.contains("history.csv") && message.contains("disk full"),
            "{message}"
        );
        assert_eq!(std::fs::read_to_string(&path).unwrap(), whole);
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["history.csv"], "a temporary file was left behind");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
