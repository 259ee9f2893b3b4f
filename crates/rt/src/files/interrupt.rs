//! SIGINT and SIGTERM: the temporaries being written are removed, then rt exits with
//! the status a shell gives a process killed by that signal (130, 143). Installed with
//! the first temporary; until then there is nothing to clean up and the signals keep
//! their default action.

use std::sync::Once;

pub fn install() {
    static INSTALL: Once = Once::new();
    INSTALL.call_once(|| {
        use signal_hook::consts::{SIGINT, SIGTERM};
        let mut signals = match signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) {
            Ok(signals) => signals,
            Err(e) => {
                log::warn!("cannot handle SIGINT/SIGTERM ({e}): an interrupted write may leave its temporary");
                return;
            }
        };
        // The handler itself only wakes this thread, which may take locks and remove files.
        let spawned = std::thread::Builder::new().name("rt-signals".into()).spawn(move || {
            if let Some(signal) = signals.forever().next() {
                super::output::remove_temporaries_in_progress();
                eprintln!("rt: interrupted (signal {signal}); partial files removed");
                let _ = std::io::Write::flush(&mut std::io::stdout());
                // `_exit`, not `exit`: exit's handlers tear down the GPU driver while the
                // render threads still use it, which NVIDIA's Vulkan driver answers with a
                // segmentation fault instead of the signal's status.
                // SAFETY: ends the process at once; nothing after it runs.
                unsafe { libc::_exit(128 + signal) };
            }
        });
        if let Err(e) = spawned {
            log::warn!("cannot start the signal thread ({e}): an interrupted write may leave its temporary");
        }
    });
}
