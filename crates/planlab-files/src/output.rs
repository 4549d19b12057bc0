//! Every file planlab's native front ends write (the CLI, the Python
//! package) goes through here: to a temporary file beside the target,
//! renamed over it only once the whole output is written (a failed command
//! leaves the old file, a reader never sees half of one, and a symlink
//! planted at the target is replaced, not followed), and never over an
//! input of the same command.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Whether `a` and `b` name the same file (or `b` lies inside folder `a`).
pub fn same_file(a: &Path, b: &Path) -> bool {
    // Hard links and bind mounts share no path: compare the inode.
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            if ma.dev() == mb.dev() && ma.ino() == mb.ino() {
                return true;
            }
        }
    }
    let canon = |p: &Path| std::fs::canonicalize(p).ok();
    // The output may not exist yet: compare its folder's canonical path.
    let out = canon(b).or_else(|| {
        let parent = b.parent().filter(|p| !p.as_os_str().is_empty());
        let parent = parent.unwrap_or_else(|| Path::new("."));
        Some(canon(parent)?.join(b.file_name()?))
    });
    match (canon(a), out) {
        (Some(a), Some(b)) => a == b || b.starts_with(&a) && a.is_dir(),
        _ => false,
    }
}

/// Refuses the output `out` (given with `flag`) when it is one of `inputs`:
/// writing it would destroy what the command read.
pub fn refuse_input(flag: &str, out: &Path, inputs: &[PathBuf]) -> Result<(), String> {
    match inputs.iter().find(|i| same_file(i, out)) {
        Some(_) => Err(format!(
            "{flag} {}: that is an input of the run; choose another file",
            out.display()
        )),
        None => Ok(()),
    }
}

/// An output being written: bytes go to a temporary file beside `out`;
/// [`AtomicFile::commit`] renames it over `out`, and dropping it
/// uncommitted removes it.
pub struct AtomicFile {
    out: PathBuf,
    tmp: PathBuf,
    file: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file (so a folder that cannot be written fails
    /// before any work).
    pub fn create(out: &Path) -> Result<Self, String> {
        let cannot = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", out.display());
        let name = out
            .file_name()
            .ok_or_else(|| format!("{}: not a file name", out.display()))?;
        // `create_new` (O_EXCL) never opens an existing file or follows a
        // link planted at the temporary name; a taken name is skipped.
        for n in 0..100u32 {
            let mut tmp_name = std::ffi::OsString::from(".");
            tmp_name.push(name);
            tmp_name.push(format!(".tmp{}-{n}", std::process::id()));
            let tmp = out.with_file_name(tmp_name);
            match std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&tmp)
            {
                Ok(f) => {
                    // A replaced file keeps its permissions.
                    if let Ok(m) = std::fs::symlink_metadata(out) {
                        if m.is_file() {
                            let _ = f.set_permissions(m.permissions());
                        }
                    }
                    return Ok(AtomicFile {
                        out: out.to_path_buf(),
                        tmp,
                        file: Some(BufWriter::new(f)),
                    });
                }
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(cannot(&e)),
            }
        }
        Err(cannot(&"no free temporary name beside it"))
    }

    /// Appends `bytes`.
    pub fn write(&mut self, bytes: &[u8]) -> Result<(), String> {
        let file = self.file.as_mut().expect("written after commit");
        file.write_all(bytes)
            .map_err(|e| format!("cannot write {}: {e}", self.out.display()))
    }

    /// Puts the finished file in place of `out` (a link there is replaced,
    /// its target untouched).
    pub fn commit(mut self) -> Result<(), String> {
        let file = self.file.take().expect("committed once");
        file.into_inner()
            .map_err(|e| e.into_error())
            .and_then(|f| f.sync_all())
            .and_then(|()| std::fs::rename(&self.tmp, &self.out))
            .map_err(|e| format!("cannot write {}: {e}", self.out.display()))
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // Uncommitted (an error, or the commit failed): leave nothing behind.
        if std::fs::symlink_metadata(&self.tmp).is_ok() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Writes `bytes` to `out` through [`AtomicFile`].
pub fn write_atomically(out: &Path, bytes: &[u8]) -> Result<(), String> {
    let mut f = AtomicFile::create(out)?;
    f.write(bytes)?;
    f.commit()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("planlab-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[cfg(unix)]
    #[test]
    fn atomic_write_replaces_a_symlink_not_its_target() {
        let dir = scratch("link");
        let target = dir.join("target.txt");
        std::fs::write(&target, "keep").unwrap();
        let out = dir.join("out.json");
        std::os::unix::fs::symlink(&target, &out).unwrap();
        write_atomically(&out, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
        assert!(std::fs::symlink_metadata(&out).unwrap().is_file());
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "new");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[cfg(unix)]
    #[test]
    fn atomic_write_skips_a_link_planted_at_the_temporary_name() {
        let dir = scratch("tmplink");
        let target = dir.join("target.txt");
        std::fs::write(&target, "keep").unwrap();
        let out = dir.join("out.csv");
        let planted = dir.join(format!(".out.csv.tmp{}-0", std::process::id()));
        std::os::unix::fs::symlink(&target, &planted).unwrap();
        write_atomically(&out, b"new").unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "new");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_uncommitted_file_leaves_the_old_one_and_no_temporary() {
        let dir = scratch("drop");
        let out = dir.join("runs.csv");
        std::fs::write(&out, "old").unwrap();
        let mut f = AtomicFile::create(&out).unwrap();
        f.write(b"half").unwrap();
        drop(f);
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "old");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn an_output_in_the_current_folder_is_compared_by_its_full_path() {
        // A bare output name (`--csv s.json`) has no parent folder.
        let here = std::env::current_dir().unwrap();
        let file = here.join("Cargo.toml");
        assert!(same_file(&file, Path::new("Cargo.toml")));
        assert!(!same_file(&file, Path::new("no-such-file.csv")));
    }
}
