//! Writing a run's output files whole or not at all, all of them or none.
//!
//! An [`OutputSet`] is checked before any work is done (every destination writable, none the
//! input, no two the same), holds each output in a temporary file beside its destination
//! from its write on, and puts them all in place only at [`OutputSet::commit`]. A run that
//! fails, or is dropped, leaves every destination as it was and no temporary behind;
//! [`exit_removing_temporaries`] does the same on a signal, from a thread that waits for it.
//!
//! # Signals
//! Temporary files exist only from an output's [`OutputSet::write`] to the
//! [`OutputSet::commit`] (a temporary file made and removed at once by [`OutputSet::add`]
//! proves the directory writable before any work), so when one thread makes them a signal
//! handler needs no thread of its own to remove them ([`interrupt_flags`]): while no
//! temporary file exists, the handler ends the process at once; while one does, it only
//! records the signal, which the set's next step (a write, or the commit before its first
//! rename) answers with [`Error::Interrupted`], removing its temporaries. A commit that has
//! begun to put files in place finishes; in [`OutputSet::commit_final`], the last of a
//! process, a signal is only recorded while the files are renamed, and then ends the
//! process with success.
//!
//! # Destinations
//! * `-` is standard output.
//! * Symbolic links are followed, dangling ones too: the file a link names is written and the
//!   link stays a link.
//! * An existing regular file is replaced atomically (a new file renamed over it) and keeps
//!   its permissions (hard links to it keep the old content).
//! * Any existing destination that is not a regular file — `/dev/null`, `/dev/stdout`, a
//!   FIFO — and any link under `/dev` and `/proc` (links there name streams, such as
//!   `/dev/stderr`) are written in place, appending: renaming over them would replace the
//!   device (as root, `-o /dev/null` once turned `/dev/null` into a regular file), or the file
//!   a shell redirected standard output to. A FIFO that nobody reads is an error, not a wait.
//!   New and regular files under `/dev` (on the tmpfs `/dev/shm`) are written as anywhere
//!   else.
//!
//! Temporary files are created with `O_EXCL` under a random name (`tempfile`), so a link
//! planted at a predictable name cannot redirect the write; their names are short whatever
//! the destination's name. They are not `fsync`ed before the rename (as potrace, vtracer and
//! most converters do not; it cost 0.65 ms of wall time per run, a sixth of a glyph's): after
//! a system crash that ext4 survives with the old or the new file, some filesystems (XFS) may
//! leave an empty one.

use crate::error::Error;
use std::fs::{File, Metadata, OpenOptions, Permissions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};
use std::sync::{Arc, LazyLock, Mutex, MutexGuard};

/// Temporary files not yet put in place or removed, for [`exit_removing_temporaries`].
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// True while no temporary file exists: cleared (under [`PENDING`]'s lock) before one is
/// created, set when the last is renamed or removed.
static NO_TEMPORARIES: LazyLock<Arc<AtomicBool>> =
    LazyLock::new(|| Arc::new(AtomicBool::new(true)));

/// How far the process' last commit ([`OutputSet::commit_final`]) has come: [`RUNNING`],
/// [`CHECKING`] or [`PUTTING`].
static LAST_COMMIT: AtomicU8 = AtomicU8::new(RUNNING);
/// No last commit has begun.
const RUNNING: u8 = 0;
/// The last commit has begun: a signal recorded before is looked for, and
/// [`NO_TEMPORARIES`] is no longer set when the temporary files are gone (only while
/// standard output and devices are written).
const CHECKING: u8 = 1;
/// The last commit puts the files in place (or has): a recorded signal no longer stops the
/// run.
const PUTTING: u8 = 2;

/// True once the last commit has put every file in place: see [`InterruptFlags`].
static FINISHED: LazyLock<Arc<AtomicBool>> = LazyLock::new(|| Arc::new(AtomicBool::new(false)));

/// The number of the signal a handler recorded, 0 for none.
static CAUGHT: LazyLock<Arc<AtomicUsize>> = LazyLock::new(|| Arc::new(AtomicUsize::new(0)));

/// The flags a signal handler shares with every [`OutputSet`] of the process, for handlers
/// that cannot remove files themselves (see the module documentation).
///
/// With the signal-hook crate, for each signal `sig`:
/// `flag::register_usize(sig, flags.caught, sig as usize)`,
/// `flag::register_conditional_shutdown(sig, 128 + sig, flags.no_temporaries)` and
/// `flag::register_conditional_shutdown(sig, 0, flags.finished)`, in that order (record,
/// then end): whatever thread runs the handler, either it finds the flag cleared or the
/// thread about to create a temporary file finds the signal and makes none. A recorded
/// signal is answered by the sets that hold temporary files, at their next step; the caller
/// ends the process then (with several sets written from several threads, a thread that
/// calls [`exit_removing_temporaries`] answers every set at once). Once the process' last
/// commit ([`OutputSet::commit_final`]) has put its files in place, a signal ends the
/// process with success (but while it writes standard output or a device: with 128 + the
/// signal, the files in place).
#[derive(Clone, Debug)]
pub struct InterruptFlags {
    /// True while no temporary file exists: the thread that creates one clears it first
    /// (also for the file [`OutputSet::add`] makes and removes at once) and then looks for
    /// a recorded signal, and it is set again when the last one is renamed or removed —
    /// from an [`OutputSet::commit_final`] on, only while standard output or a device is
    /// written. Not to be stored by anyone else.
    pub no_temporaries: Arc<AtomicBool>,
    /// Where a handler stores the signal's number; an output set that holds temporary files
    /// stops with [`Error::Interrupted`] at its next step once it is not 0.
    pub caught: Arc<AtomicUsize>,
    /// True once an [`OutputSet::commit_final`] has put its files in place: the run is
    /// over. Not to be stored by anyone else.
    pub finished: Arc<AtomicBool>,
}

/// The process' [`InterruptFlags`].
///
/// ```
/// let flags = layertrace::interrupt_flags();
/// // No output set holds a temporary file outside its writes and commit.
/// assert!(flags.no_temporaries.load(std::sync::atomic::Ordering::SeqCst));
/// ```
pub fn interrupt_flags() -> InterruptFlags {
    InterruptFlags {
        no_temporaries: Arc::clone(&NO_TEMPORARIES),
        caught: Arc::clone(&CAUGHT),
        finished: Arc::clone(&FINISHED),
    }
}

impl InterruptFlags {
    /// The signal a handler recorded in `caught`, if any — none once the process' last
    /// commit ([`OutputSet::commit_final`]) has begun to put files in place: a signal then
    /// stops nothing, and an error after it is the run's own.
    pub fn recorded(&self) -> Option<i32> {
        if LAST_COMMIT.load(Ordering::SeqCst) == PUTTING {
            return None;
        }
        match self.caught.load(Ordering::SeqCst) {
            0 => None,
            sig => Some(i32::try_from(sig).unwrap_or(i32::MAX)),
        }
    }
}

/// [`Error::Interrupted`] if a handler recorded a signal.
fn check_caught() -> Result<(), Error> {
    match interrupt_flags().recorded() {
        None => Ok(()),
        Some(signal) => Err(Error::Interrupted { signal }),
    }
}

/// Sets [`NO_TEMPORARIES`] again if `list` (the locked [`PENDING`]) is empty and no last
/// commit has begun.
fn settle(list: &[PathBuf]) {
    if list.is_empty() && LAST_COMMIT.load(Ordering::SeqCst) == RUNNING {
        NO_TEMPORARIES.store(true, Ordering::SeqCst);
    }
}

/// Removes `path` from the list, setting [`NO_TEMPORARIES`] when it empties.
fn forget(list: &mut Vec<PathBuf>, path: &Path) {
    list.retain(|p| p != path);
    settle(list);
}

/// Removes every temporary file of every [`OutputSet`] of the process and exits with `code`,
/// without returning: for a thread that waits for signals (SIGINT, SIGTERM), or after
/// [`Error::Interrupted`]. Not from a signal handler itself: it locks, allocates and calls
/// `exit`. No output set can create or rename a temporary file once this has started —
/// but once the process' last commit ([`OutputSet::commit_final`]) has begun to put its
/// files in place, it waits for the renames and exits with success (with `code` while
/// standard output or a device is written), as the handlers of [`InterruptFlags`] do.
///
/// ```
/// // On a thread of its own (here with signal-hook's `iterator` feature):
/// // let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])?;
/// // std::thread::spawn(move || {
/// //     if let Some(sig) = signals.forever().next() {
/// //         layertrace::exit_removing_temporaries(128 + sig)
/// //     }
/// // });
/// let _: fn(i32) -> ! = layertrace::exit_removing_temporaries;
/// ```
pub fn exit_removing_temporaries(code: i32) -> ! {
    loop {
        let list = pending();
        if LAST_COMMIT.load(Ordering::SeqCst) != PUTTING {
            for path in list.iter() {
                let _ = std::fs::remove_file(path);
            }
            // The lock stays held: `exit` does not unwind, so no other thread can add or
            // rename a file.
            std::process::exit(code)
        }
        // The process' last commit puts its files in place: as the handlers of
        // `InterruptFlags` do, end it with `code` while it writes standard output or a
        // device, with success once it is done, and else wait for the renames.
        if NO_TEMPORARIES.load(Ordering::SeqCst) {
            std::process::exit(code)
        }
        if FINISHED.load(Ordering::SeqCst) {
            std::process::exit(0)
        }
        drop(list);
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
}

/// A temporary file beside a destination, registered for removal on signals.
struct Temp {
    file: Option<tempfile::NamedTempFile>,
    path: PathBuf,
}

impl Temp {
    fn create(dir: &Path, mode: Option<&Permissions>) -> std::io::Result<Temp> {
        let mut list = pending();
        // From here on a handler only records a signal: the file may exist before the list
        // names it. Then a signal recorded before is looked for: a handler records before
        // it reads the flag, and all four accesses are sequentially consistent, so either
        // it reads the flag cleared or this reads its signal — whatever thread it runs on.
        NO_TEMPORARIES.store(false, Ordering::SeqCst);
        if interrupt_flags().recorded().is_some() {
            settle(&list);
            return Err(std::io::ErrorKind::Interrupted.into());
        }
        let mut b = tempfile::Builder::new();
        b.prefix(".layertrace-").suffix(".tmp").rand_bytes(10);
        if let Some(mode) = mode {
            b.permissions(mode.clone());
        } else {
            #[cfg(unix)]
            {
                // What `File::create` would give: 0666 less the umask.
                use std::os::unix::fs::PermissionsExt;
                b.permissions(Permissions::from_mode(0o666));
            }
        }
        let file = b.tempfile_in(dir).inspect_err(|_| settle(&list))?;
        let path = file.path().to_path_buf();
        list.push(path.clone());
        Ok(Temp {
            file: Some(file),
            path,
        })
    }

    fn persist(mut self, target: &Path) -> std::io::Result<()> {
        let mut list = pending();
        let file = self.file.take().expect("a temporary is persisted once");
        let result = file.persist(target).map(drop).map_err(|e| e.error);
        // On failure the file is removed by the dropped `PersistError`.
        forget(&mut list, &self.path);
        result
    }
}

impl Drop for Temp {
    fn drop(&mut self) {
        if let Some(file) = self.file.take() {
            let mut list = pending();
            drop(file); // removes it, while the list still names it
            forget(&mut list, &self.path);
        }
    }
}

/// Bytes written between two looks for a recorded signal in [`OutputSet::write`].
const WRITE_PIECE: usize = 1 << 22;

/// A temporary file in `dir` for the output `path`: [`Error::Interrupted`] if a signal was
/// recorded before it was made or meanwhile (then it is removed), else [`Error::Write`] if
/// it cannot be made.
fn make_temp(dir: &Path, mode: Option<&Permissions>, path: &Path) -> Result<Temp, Error> {
    let made = Temp::create(dir, mode);
    check_caught()?;
    made.map_err(|source| Error::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// Identity of an existing file (device and inode on Unix).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct FileId(u64, u64);

impl FileId {
    #[cfg(unix)]
    fn of(m: &Metadata) -> Option<FileId> {
        use std::os::unix::fs::MetadataExt;
        Some(FileId(m.dev(), m.ino()))
    }

    #[cfg(not(unix))]
    fn of(_: &Metadata) -> Option<FileId> {
        None
    }
}

/// Where an output goes.
enum Sink {
    /// Standard output, written at commit.
    Stdout { bytes: Option<Vec<u8>> },
    /// A device, FIFO or stream, opened at check time, written at commit, appending.
    InPlace { file: File, bytes: Option<Vec<u8>> },
    /// A regular file (new or replaced): the temporary beside it, made and filled by
    /// `write` in `dir` (with the replaced file's permissions, `mode`).
    Replace {
        target: PathBuf,
        dir: PathBuf,
        mode: Option<Permissions>,
        temp: Option<Temp>,
    },
}

struct Entry {
    /// The path as the user gave it (for messages).
    path: PathBuf,
    /// What makes two destinations the same.
    key: Key,
    sink: Sink,
}

#[derive(PartialEq, Eq)]
enum Key {
    Stdout,
    File {
        canonical: PathBuf,
        id: Option<FileId>,
    },
}

impl Key {
    fn same(&self, other: &Key) -> bool {
        match (self, other) {
            (Key::Stdout, Key::Stdout) => true,
            (
                Key::File { canonical, id },
                Key::File {
                    canonical: c2,
                    id: id2,
                },
            ) => canonical == c2 || (id.is_some() && id == id2),
            _ => false,
        }
    }
}

/// Names one output of an [`OutputSet`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutputId(usize);

/// The outputs of one run, written all together or not at all (see the module docs).
///
/// ```
/// let dir = tempfile::tempdir().unwrap();
/// let mut outs = layertrace::OutputSet::new(None);
/// let svg = outs.add(&dir.path().join("a.svg")).unwrap();
/// let json = outs.add(&dir.path().join("a.json")).unwrap();
/// outs.write(svg, b"<svg/>".to_vec()).unwrap();
/// outs.write(json, b"{}".to_vec()).unwrap();
/// // Nothing is in place before the commit.
/// assert!(!dir.path().join("a.svg").exists());
/// outs.commit().unwrap();
/// assert_eq!(std::fs::read(dir.path().join("a.json")).unwrap(), b"{}");
/// ```
pub struct OutputSet {
    input: Option<FileId>,
    entries: Vec<Entry>,
}

impl OutputSet {
    /// An empty set for a run reading `input` (a file path, or `None` for standard input or
    /// in-memory data), which no output may name.
    pub fn new(input: Option<&Path>) -> OutputSet {
        let input = input
            .filter(|p| *p != Path::new("-"))
            .and_then(|p| std::fs::metadata(p).ok())
            .and_then(|m| FileId::of(&m));
        OutputSet {
            input,
            entries: Vec::new(),
        }
    }

    /// Checks the destination `path` and prepares it: a temporary file made and removed
    /// beside it (so its directory is known to be writable), or the device opened. Nothing
    /// visible changes.
    ///
    /// Errors: [`Error::OutputIsInput`] if it resolves to the input file,
    /// [`Error::SameOutput`] if another output of the set goes to the same place,
    /// [`Error::Write`] if it cannot be written (missing or read-only directory, a directory,
    /// a FIFO without a reader, closed standard output), [`Error::Interrupted`] if a signal
    /// was recorded (see [`interrupt_flags`]).
    pub fn add(&mut self, path: &Path) -> Result<OutputId, Error> {
        let err = |source| Error::Write {
            path: path.to_path_buf(),
            source,
        };
        let (key, sink) = if path == Path::new("-") || is_stdout_alias(path) {
            check_stdout().map_err(err)?;
            (Key::Stdout, Sink::Stdout { bytes: None })
        } else {
            let (target, special) = resolve(path).map_err(err)?;
            let meta = match std::fs::metadata(&target) {
                Ok(meta) => Some(meta),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
                Err(e) => return Err(err(e)),
            };
            let id = meta.as_ref().and_then(FileId::of);
            if id.is_some() && id == self.input {
                return Err(Error::OutputIsInput {
                    path: path.to_path_buf(),
                });
            }
            if meta.as_ref().is_some_and(Metadata::is_dir) {
                return Err(err(std::io::Error::new(
                    std::io::ErrorKind::IsADirectory,
                    "is a directory",
                )));
            }
            // A path that cannot be resolved (a stream under /proc) is compared as written.
            let canonical = canonical(&target).unwrap_or_else(|_| target.clone());
            let key = Key::File { canonical, id };
            // Under /dev and /proc, only what exists and is not a plain file is a device or
            // stream: a new or regular file there (on /dev/shm, a tmpfs) is written as
            // anywhere else, not appended to.
            let stream = special
                && std::fs::symlink_metadata(&target)
                    .is_ok_and(|m| m.file_type().is_symlink() || !m.is_file());
            if stream || meta.as_ref().is_some_and(|m| !m.is_file()) {
                let file = open_in_place(&target).map_err(err)?;
                (key, Sink::InPlace { file, bytes: None })
            } else {
                let dir = match target.parent() {
                    Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
                    _ => PathBuf::from("."),
                };
                let mode = meta.map(|m| m.permissions());
                drop(make_temp(&dir, mode.as_ref(), path)?);
                // A signal recorded while the probe existed would wait for the first write.
                check_caught()?;
                let sink = Sink::Replace {
                    target,
                    dir,
                    mode,
                    temp: None,
                };
                (key, sink)
            }
        };
        if let Some(other) = self.entries.iter().find(|e| e.key.same(&key)) {
            return Err(Error::SameOutput {
                first: other.path.clone(),
                second: path.to_path_buf(),
            });
        }
        self.entries.push(Entry {
            path: path.to_path_buf(),
            key,
            sink,
        });
        Ok(OutputId(self.entries.len() - 1))
    }

    /// Gives output `id` its content: written to its temporary file now, or kept for the
    /// commit (standard output, devices). Writing an output twice replaces nothing: the
    /// second call is an error. [`Error::Interrupted`] if a signal was recorded before or
    /// while writing (see [`interrupt_flags`]).
    pub fn write(&mut self, id: OutputId, bytes: Vec<u8>) -> Result<(), Error> {
        let entry = &mut self.entries[id.0];
        let err = |source| Error::Write {
            path: entry.path.clone(),
            source,
        };
        let twice = || std::io::Error::other("written twice");
        match &mut entry.sink {
            Sink::Stdout { bytes: slot } | Sink::InPlace { bytes: slot, .. } => {
                if slot.is_some() {
                    return Err(err(twice()));
                }
                *slot = Some(bytes);
                Ok(())
            }
            Sink::Replace {
                dir, mode, temp, ..
            } => {
                if temp.is_some() {
                    return Err(err(twice()));
                }
                let temp = temp.insert(make_temp(dir, mode.as_ref(), &entry.path)?);
                let file = temp.file.as_mut().expect("not yet persisted");
                // In pieces, a recorded signal looked for after each: a large output on slow
                // storage does not hold up the answer.
                for piece in bytes.chunks(WRITE_PIECE) {
                    file.write_all(piece).map_err(err)?;
                    check_caught()?;
                }
                file.flush().map_err(err)
            }
        }
    }

    /// Puts every written output in place: regular files first (renames), then standard
    /// output and devices. An output that was added but never written is left untouched.
    /// Once a rename has succeeded it is not undone if a later one fails.
    /// [`Error::Interrupted`], with nothing put in place, if a signal was recorded before
    /// (see [`interrupt_flags`]).
    pub fn commit(self) -> Result<(), Error> {
        // The last moment a signal stops the run: from the first rename on, it finishes.
        check_caught()?;
        self.put_in_place(false)
    }

    /// [`OutputSet::commit`] for the last set of a process whose work ends with it, so that
    /// a signal that comes once files are being put in place does not end the process as if
    /// nothing had been written (with 128 + its number, which says that no destination
    /// changed): with the handlers of [`interrupt_flags`], from here on a signal is only
    /// recorded (and no longer [`InterruptFlags::recorded`]) while the files are renamed,
    /// then ends the process with success once they are in place (`finished`), but with
    /// 128 + its number while standard output or a device is written (a reader that stopped
    /// reading must not hold the process). [`Error::Interrupted`], with nothing put in place,
    /// if a signal was recorded before. No other set should be made after it.
    pub fn commit_final(self) -> Result<(), Error> {
        {
            let _list = pending();
            // Cleared, then a recorded signal looked for (the order `Temp::create` follows):
            // a handler either reads the flag cleared or its signal is found here.
            LAST_COMMIT.store(CHECKING, Ordering::SeqCst);
            NO_TEMPORARIES.store(false, Ordering::SeqCst);
        }
        check_caught()?;
        LAST_COMMIT.store(PUTTING, Ordering::SeqCst);
        self.put_in_place(true)
    }

    /// Renames the written outputs into place, then writes standard output and devices;
    /// `finishing`: [`OutputSet::commit_final`]'s (see there).
    fn put_in_place(self, finishing: bool) -> Result<(), Error> {
        let mut streams = Vec::new();
        for entry in self.entries {
            let err = |source| Error::Write {
                path: entry.path.clone(),
                source,
            };
            match entry.sink {
                Sink::Replace { target, temp, .. } => {
                    if let Some(temp) = temp {
                        temp.persist(&target).map_err(err)?;
                    }
                }
                Sink::Stdout { bytes: Some(b) } => streams.push((entry.path, None, b)),
                Sink::InPlace {
                    file,
                    bytes: Some(b),
                } => streams.push((entry.path, Some(file), b)),
                Sink::Stdout { bytes: None } | Sink::InPlace { bytes: None, .. } => {}
            }
        }
        if !finishing {
            return write_streams(streams);
        }
        // Every file in place: from here on a signal ends the process with success — but
        // while standard output and devices are written (a reader that stopped reading
        // must not hold it), with 128 + the signal (its handler comes first).
        FINISHED.store(true, Ordering::SeqCst);
        if streams.is_empty() {
            return Ok(());
        }
        NO_TEMPORARIES.store(true, Ordering::SeqCst);
        let written = write_streams(streams);
        NO_TEMPORARIES.store(false, Ordering::SeqCst);
        written
    }
}

/// Writes standard output and devices, in order.
fn write_streams(streams: Vec<(PathBuf, Option<File>, Vec<u8>)>) -> Result<(), Error> {
    for (path, file, bytes) in streams {
        let result = match file {
            Some(mut f) => f.write_all(&bytes).and_then(|()| f.flush()),
            None => {
                let mut out = std::io::stdout().lock();
                out.write_all(&bytes).and_then(|()| out.flush())
            }
        };
        result.map_err(|source| Error::Write { path, source })?;
    }
    Ok(())
}

/// Writes `bytes` to `path` whole or not at all: an [`OutputSet`] of one output (see the
/// module docs for what happens with links, devices and existing files).
///
/// ```
/// use layertrace::write_atomic;
/// let dir = tempfile::tempdir().unwrap();
/// let path = dir.path().join("out.svg");
/// write_atomic(&path, b"<svg/>")?;
/// assert_eq!(std::fs::read(&path).unwrap(), b"<svg/>");
/// # Ok::<(), layertrace::Error>(())
/// ```
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let mut set = OutputSet::new(None);
    let id = set.add(path)?;
    set.write(id, bytes.to_vec())?;
    set.commit()
}

/// `/dev/stdout` and its aliases name standard output: two of them in one run are one place.
pub(crate) fn is_stdout_alias(path: &Path) -> bool {
    ["/dev/stdout", "/dev/fd/1", "/proc/self/fd/1"]
        .iter()
        .any(|a| path == Path::new(a))
}

/// Standard output is usable: on Linux, not the `/dev/null` that Rust's runtime opens
/// (read-write) in place of a closed descriptor 1 (`>&-`), where the output would be lost.
fn check_stdout() -> std::io::Result<()> {
    #[cfg(target_os = "linux")]
    {
        let target = std::fs::read_link("/proc/self/fd/1");
        let info = std::fs::read_to_string("/proc/self/fdinfo/1");
        if let (Ok(target), Ok(info)) = (target, info) {
            let flags = info
                .lines()
                .find_map(|l| l.strip_prefix("flags:"))
                .and_then(|f| u32::from_str_radix(f.trim(), 8).ok());
            // O_ACCMODE == 3, O_RDWR == 2: a shell's `> /dev/null` opens write-only.
            if target == Path::new("/dev/null") && flags.is_some_and(|f| f & 3 == 2) {
                return Err(std::io::Error::other("standard output is closed"));
            }
        }
    }
    Ok(())
}

/// Opens a device, FIFO or stream for appending. A FIFO nobody reads fails at once (ENXIO)
/// instead of blocking; the descriptor is made blocking again for the write.
fn open_in_place(target: &Path) -> std::io::Result<File> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        let file = OpenOptions::new()
            .append(true)
            .custom_flags(nix::fcntl::OFlag::O_NONBLOCK.bits())
            .open(target)
            .map_err(|e| {
                if e.raw_os_error() == Some(nix::errno::Errno::ENXIO as i32) {
                    std::io::Error::other("no process is reading this FIFO")
                } else {
                    e
                }
            })?;
        use nix::fcntl::{fcntl, FcntlArg, OFlag};
        let flags = fcntl(&file, FcntlArg::F_GETFL).map_err(std::io::Error::from)?;
        let flags = OFlag::from_bits_truncate(flags) - OFlag::O_NONBLOCK;
        fcntl(&file, FcntlArg::F_SETFL(flags)).map_err(std::io::Error::from)?;
        Ok(file)
    }
    #[cfg(not(unix))]
    {
        OpenOptions::new().append(true).open(target)
    }
}

/// The absolute path of `target` with every link resolved; for a file that does not exist
/// yet, its directory's canonical path joined with its name.
fn canonical(target: &Path) -> std::io::Result<PathBuf> {
    match std::fs::canonicalize(target) {
        Ok(p) => Ok(p),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            let dir = match target.parent() {
                Some(d) if !d.as_os_str().is_empty() => d,
                _ => Path::new("."),
            };
            let name = target.file_name().ok_or_else(|| {
                std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name")
            })?;
            Ok(std::fs::canonicalize(dir)?.join(name))
        }
        Err(e) => Err(e),
    }
}

/// `path` with its symbolic links followed (a dangling link gives the path it names), and
/// whether it lies under `/dev` or `/proc`, where paths name devices and streams (following
/// `/dev/stdout` further would reach the file standard output was redirected to).
fn resolve(path: &Path) -> std::io::Result<(PathBuf, bool)> {
    let special = |p: &Path| p.starts_with("/dev") || p.starts_with("/proc");
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        if special(&p) {
            return Ok((p, true));
        }
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&p)?;
                p = match p.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            Ok(_) => return Ok((p, false)),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((p, false)),
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// Encodes a picture as PNG in memory.
///
/// ```
/// use layertrace::png_bytes;
/// let img = image::RgbImage::from_pixel(3, 2, image::Rgb([255, 0, 0]));
/// let bytes = png_bytes(&img).unwrap();
/// assert_eq!(&bytes[1..4], b"PNG");
/// ```
pub fn png_bytes(img: &image::RgbImage) -> Result<Vec<u8>, image::ImageError> {
    let mut buf = std::io::Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Png)?;
    Ok(buf.into_inner())
}

#[cfg(test)]
mod tests;
