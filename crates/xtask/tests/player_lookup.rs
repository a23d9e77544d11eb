//! `cargo play`'s choice of player (issue 22), without a display: fake PATH and game
//! directories holding fake players.

use std::ffi::OsString;
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};

use portalcast_xtask::player::{find_player, player_args};

/// A fresh directory under the system's temporary directory.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("portalcast-player-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("creating a scratch directory");
    dir
}

/// Writes a file named `name` in `dir`, executable or not.
fn player(dir: &Path, name: &str, executable: bool) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, "#!/bin/sh\n").expect("writing a fake player");
    let mode = if executable { 0o755 } else { 0o644 };
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(mode)).expect("chmod");
    path
}

#[test]
fn the_qt_player_wins_and_usr_games_is_searched() {
    let (bin, games, empty) = (scratch("bin"), scratch("games"), scratch("empty"));
    let path: OsString = std::env::join_paths([&empty, &bin]).expect("a PATH");
    // Debian's mgba-sdl: /usr/games/mgba, off root's PATH.
    let sdl = player(&games, "mgba", true);
    assert_eq!(
        find_player(Some(&path), std::slice::from_ref(&games)),
        Some(sdl.clone())
    );
    // Not found where nobody looks.
    assert_eq!(find_player(Some(&path), &[]), None);
    // mgba-qt on PATH is preferred to the SDL player in /usr/games.
    let qt = player(&bin, "mgba-qt", true);
    assert_eq!(
        find_player(Some(&path), std::slice::from_ref(&games)),
        Some(qt)
    );
    // A file that is not executable is no player.
    std::fs::remove_file(bin.join("mgba-qt")).expect("removing");
    player(&bin, "mgba-qt", false);
    assert_eq!(
        find_player(Some(&path), std::slice::from_ref(&games)),
        Some(sdl)
    );
    // No PATH at all: the game directories still count.
    assert!(find_player(None, std::slice::from_ref(&games)).is_some());
    for dir in [bin, games, empty] {
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn the_player_prints_the_rom_s_log_lines() {
    let args = player_args(Path::new("target/portalcast.gba"));
    let words: Vec<&str> = args
        .iter()
        .map(|arg| arg.to_str().expect("UTF-8"))
        .collect();
    assert_eq!(
        words,
        ["-C", "logToStdout=1", "-l", "15", "target/portalcast.gba"]
    );
}
