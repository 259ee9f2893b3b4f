//! One libFuzzer binary for every target (`rt_watch::stream::fuzz_targets`: `rt::fuzz`'s and
//! the viewport stream's): `RT_FUZZ_TARGET` names which.
#![no_main]

use libfuzzer_sys::fuzz_target;
use std::sync::OnceLock;

struct Chosen {
    target: &'static rt::fuzz::Target,
    workspace: rt::fuzz::Workspace,
}

fn chosen() -> &'static Chosen {
    static CHOSEN: OnceLock<Chosen> = OnceLock::new();
    CHOSEN.get_or_init(|| {
        let name = std::env::var("RT_FUZZ_TARGET").unwrap_or_default();
        let targets = rt_watch::stream::fuzz_targets();
        let target = targets.iter().copied().find(|t| t.name == name).unwrap_or_else(|| {
            let names: Vec<&str> = targets.iter().map(|t| t.name).collect();
            panic!("RT_FUZZ_TARGET={name:?}: name one of {}", names.join(", "))
        });
        let workspace = rt::fuzz::Workspace::new().expect("a scratch folder for the target's files");
        Chosen { target, workspace }
    })
}

fuzz_target!(|data: &[u8]| {
    let chosen = chosen();
    let _ = chosen.target.run(&chosen.workspace, data);
});
