//! Atomic output: write to a temporary file in the destination folder, then rename.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use super::error::{IoError, IoResult};

/// The temporary path used while `dest` is being written.
pub fn temp_path(dest: &Path) -> PathBuf {
    let name = dest.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
    dest.with_file_name(format!(".{name}.qmesh-tmp-{}", std::process::id()))
}

/// Removes temporaries of `dest` left by runs that were killed (their process is gone;
/// checked through /proc, so only on Linux).
fn remove_stale_temporaries(dest: &Path) {
    let (Some(dir), Some(name)) = (dest.parent(), dest.file_name()) else { return };
    let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    let prefix = format!(".{}.qmesh-tmp-", name.to_string_lossy());
    if !Path::new("/proc/self").exists() {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for e in entries.flatten() {
        let f = e.file_name().to_string_lossy().into_owned();
        if let Some(pid) = f.strip_prefix(&prefix).and_then(|p| p.parse::<u32>().ok())
            && !Path::new(&format!("/proc/{pid}")).exists()
        {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Runs `body` on a buffered writer to a temporary file, then renames it onto `dest`.
/// On any error the temporary file is removed and `dest` is left untouched.
pub fn write_atomically(dest: &Path, body: impl FnOnce(&mut dyn Write) -> IoResult<()>) -> IoResult<()> {
    let folder = dest.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    if !folder.is_dir() {
        return Err(IoError::unsupported(
            dest,
            format!("cannot write here: the folder {} does not exist", folder.display()),
        ));
    }
    if dest.is_dir() {
        return Err(IoError::unsupported(dest, "this is a folder: give a file name to write"));
    }
    remove_stale_temporaries(dest);
    let tmp = temp_path(dest);
    let result = (|| {
        let f = File::create(&tmp).map_err(|e| IoError::io(dest, e))?;
        let mut w = BufWriter::with_capacity(1 << 20, f);
        body(&mut w)?;
        let f = w.into_inner().map_err(|e| IoError::io(dest, e.into_error()))?;
        f.sync_all().map_err(|e| IoError::io(dest, e))?;
        std::fs::rename(&tmp, dest).map_err(|e| IoError::io(dest, e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}
