//! One client of `rt watch --stream`: its command lines, read on a thread of their own
//! so that rendering never waits for them, and the messages and frames written back.
//! A client that goes away (end of input, a closed pipe or socket) is an event like any
//! other, never a crash: writes that fail with EPIPE mark it gone.
//!
//! What waits between the reader and the renderer is bounded, however fast a client
//! writes. `camera`, `size` and `spp` set state, so a newer one replaces an older one of
//! its kind still waiting (which is then neither applied nor answered: the latest camera
//! wins). Other lines (`reload`, `quit`, refused lines) are kept in order, at most
//! [`QUEUE_LIMIT`] of them: beyond that the reader stops reading until the renderer has
//! taken them, and the client's writes wait.

use super::command::{Command, parse};
use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Read, Write};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};

/// Longer lines are refused (and skipped to their end) rather than held in memory.
const MAX_LINE: u64 = 64 * 1024;

/// Lines that cannot be merged and wait for the renderer, at most.
pub const QUEUE_LIMIT: usize = 64;

/// Line `line` (1-based, blank lines counted) was a command, or this is what is wrong with it.
pub type Line = (u64, Result<Command, String>);

/// What the client sent since the renderer last looked.
pub struct Batch {
    /// In the order sent, superseded state commands left out.
    pub lines: Vec<Line>,
    /// The input ended or failed after these lines: the client is gone.
    pub closed: bool,
}

#[derive(Default)]
struct Pending {
    lines: VecDeque<Line>,
    closed: bool,
    /// The renderer dropped the connection: the reader stops.
    abandoned: bool,
}

/// The lines between the reading thread and the renderer.
#[derive(Clone, Default)]
pub struct Incoming(Arc<(Mutex<Pending>, Condvar)>);

impl Incoming {
    fn lock(&self) -> MutexGuard<'_, Pending> {
        self.0.0.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    fn wait<'a>(&self, guard: MutexGuard<'a, Pending>) -> MutexGuard<'a, Pending> {
        self.0.1.wait(guard).unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    /// Everything sent since the last call; with `block`, waits until there is something.
    pub fn take(&self, block: bool) -> Batch {
        let mut pending = self.lock();
        while block && pending.lines.is_empty() && !pending.closed {
            pending = self.wait(pending);
        }
        let lines = pending.lines.drain(..).collect();
        self.0.1.notify_all();
        Batch { lines, closed: pending.closed }
    }

    /// Queues a line for the renderer (see the module's text); false once the renderer
    /// has gone.
    fn push(&self, line: Line) -> bool {
        let mut pending = self.lock();
        loop {
            if pending.abandoned {
                return false;
            }
            if let Ok(command) = &line.1
                && supersedes_itself(command)
            {
                let same = |(_, c): &Line| {
                    c.as_ref().is_ok_and(|c| std::mem::discriminant(c) == std::mem::discriminant(command))
                };
                pending.lines.retain(|l| !same(l));
                break;
            }
            let waiting = pending.lines.iter().filter(|(_, c)| !c.as_ref().is_ok_and(supersedes_itself)).count();
            if waiting < QUEUE_LIMIT {
                break;
            }
            pending = self.wait(pending);
        }
        pending.lines.push_back(line);
        self.0.1.notify_all();
        true
    }

    fn close(&self) {
        self.lock().closed = true;
        self.0.1.notify_all();
    }

    fn abandon(&self) {
        self.lock().abandoned = true;
        self.0.1.notify_all();
    }
}

/// Commands that only set state: a newer one makes an older one waiting pointless.
fn supersedes_itself(command: &Command) -> bool {
    matches!(command, Command::Camera(_) | Command::Size { .. } | Command::Spp(_))
}

/// The client closed its end while rt was writing to it.
#[derive(Debug)]
pub struct Gone;

pub struct Connection {
    pub incoming: Incoming,
    out: Box<dyn Write + Send>,
}

impl Connection {
    /// Reads commands from `input` on a new thread; writes to `output`.
    pub fn new(input: impl Read + Send + 'static, output: impl Write + Send + 'static) -> Self {
        let incoming = Incoming::default();
        let queue = incoming.clone();
        std::thread::spawn(move || {
            let mut input = BufReader::new(input);
            let mut line = 0;
            loop {
                line += 1;
                let Some(command) = read_command(&mut input) else {
                    queue.close();
                    return;
                };
                if let Some(command) = command
                    && !queue.push((line, command))
                {
                    return;
                }
            }
        });
        Self { incoming, out: Box::new(std::io::BufWriter::new(output)) }
    }

    /// Writes one message line.
    pub fn line(&mut self, text: &str) -> Result<(), Gone> {
        self.write(&[text.as_bytes(), b"\n"])
    }

    /// Writes `header` with ` bytes=N` appended, then the N bytes of `payload`.
    pub fn frame(&mut self, header: &str, payload: &[u8]) -> Result<(), Gone> {
        let header = format!("{header} bytes={}\n", payload.len());
        self.write(&[header.as_bytes(), payload])
    }

    fn write(&mut self, parts: &[&[u8]]) -> Result<(), Gone> {
        let result = parts.iter().try_for_each(|p| self.out.write_all(p)).and_then(|()| self.out.flush());
        result.map_err(|e| {
            log::info!("the stream's client is gone: {e}");
            Gone
        })
    }
}

impl Drop for Connection {
    fn drop(&mut self) {
        self.incoming.abandon();
    }
}

/// The next line's command: `None` at the end of the input; `Some(None)` for a blank line.
pub fn read_command(input: &mut impl BufRead) -> Option<Option<Result<Command, String>>> {
    let mut bytes = Vec::new();
    match input.by_ref().take(MAX_LINE).read_until(b'\n', &mut bytes) {
        Ok(0) | Err(_) => return None,
        Ok(_) => {}
    }
    if bytes.last() != Some(&b'\n') && bytes.len() as u64 == MAX_LINE {
        // Skips the rest of the line.
        let mut rest = Vec::new();
        loop {
            rest.clear();
            match input.by_ref().take(MAX_LINE).read_until(b'\n', &mut rest) {
                Ok(0) | Err(_) => return None,
                Ok(_) if rest.last() == Some(&b'\n') => break,
                Ok(_) => {}
            }
        }
        return Some(Some(Err(format!("line longer than {} KiB", MAX_LINE / 1024))));
    }
    Some(match std::str::from_utf8(&bytes) {
        Ok(text) => parse(text),
        Err(_) => Some(Err("the line is not UTF-8".into())),
    })
}
