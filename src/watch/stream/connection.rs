//! One client of `rt watch --stream`: its command lines, read on a thread of their own
//! so that rendering never waits for them, and the messages and frames written back.
//! A client that goes away (end of input, a closed pipe or socket) is an event like any
//! other, never a crash: writes that fail with EPIPE mark it gone.

use super::command::{Command, parse};
use std::io::{BufRead, BufReader, Read, Write};
use std::sync::mpsc::{Receiver, channel};

/// Longer lines are refused (and skipped to their end) rather than held in memory.
const MAX_LINE: u64 = 64 * 1024;

/// What the reading thread saw.
pub enum Incoming {
    /// Line `line` (1-based, blank lines counted) was a command, or this is what is wrong with it.
    Command { line: u64, command: Result<Command, String> },
    /// The input ended or failed: the client is gone.
    Closed,
}

/// The client closed its end while rt was writing to it.
#[derive(Debug)]
pub struct Gone;

pub struct Connection {
    pub incoming: Receiver<Incoming>,
    out: Box<dyn Write + Send>,
}

impl Connection {
    /// Reads commands from `input` on a new thread; writes to `output`.
    pub fn new(input: impl Read + Send + 'static, output: impl Write + Send + 'static) -> Self {
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            let mut input = BufReader::new(input);
            let mut line = 0;
            loop {
                line += 1;
                let Some(command) = read_command(&mut input) else {
                    let _ = tx.send(Incoming::Closed);
                    return;
                };
                if let Some(command) = command
                    && tx.send(Incoming::Command { line, command }).is_err()
                {
                    return;
                }
            }
        });
        Self { incoming: rx, out: Box::new(std::io::BufWriter::new(output)) }
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

/// The next line's command: `None` at the end of the input; `Some(None)` for a blank line.
fn read_command(input: &mut impl BufRead) -> Option<Option<Result<Command, String>>> {
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
