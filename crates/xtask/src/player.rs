//! Which mGBA `cargo play` opens the ROM in, and how: Debian's packages install `mgba-qt`
//! (`mgba-qt`) in `/usr/bin` and the SDL player (`mgba-sdl`) as `/usr/games/mgba`, and
//! `/usr/games` is not on root's PATH, which is who runs the setup.

use std::ffi::{OsStr, OsString};
use std::path::{Path, PathBuf};

/// The players, most preferred first: the Qt one has menus, a debugger and a log window.
pub const PLAYERS: [&str; 2] = ["mgba-qt", "mgba"];

/// Where Debian puts games besides PATH: looked in after it.
pub const GAME_DIRS: [&str; 2] = ["/usr/games", "/usr/local/games"];

/// The player to start: the first of [`PLAYERS`] found as an executable file in a directory of
/// `path` (a PATH value) or, after those, of `extra_dirs`; a more preferred player anywhere
/// wins over a less preferred one on PATH.
pub fn find_player(path: Option<&OsStr>, extra_dirs: &[PathBuf]) -> Option<PathBuf> {
    let mut dirs: Vec<PathBuf> = path
        .map(|path| std::env::split_paths(path).collect())
        .unwrap_or_default();
    dirs.extend(extra_dirs.iter().cloned());
    PLAYERS.iter().find_map(|name| {
        dirs.iter()
            .map(|dir| dir.join(name))
            .find(|candidate| is_executable(candidate))
    })
}

/// [`find_player`] on this process's PATH and [`GAME_DIRS`].
pub fn find_installed_player() -> Option<PathBuf> {
    let games: Vec<PathBuf> = GAME_DIRS.iter().map(PathBuf::from).collect();
    find_player(std::env::var_os("PATH").as_deref(), &games)
}

/// The arguments that open `gba` in a player with the ROM's log lines on the terminal (mGBA's
/// `logToStdout`, as agb's runner does), fatal to info levels (mask 15).
pub fn player_args(gba: &Path) -> Vec<OsString> {
    let mut args: Vec<OsString> = ["-C", "logToStdout=1", "-l", "15"]
        .iter()
        .map(OsString::from)
        .collect();
    args.push(gba.as_os_str().to_owned());
    args
}

/// What `cargo play` says when it finds no player.
pub fn no_player_message() -> String {
    format!(
        "no mGBA found ({} looked for on PATH and in {}): install mgba-qt or mgba-sdl to play in a window",
        PLAYERS.join(" and "),
        GAME_DIRS.join(", ")
    )
}

fn is_executable(path: &Path) -> bool {
    use std::os::unix::fs::PermissionsExt;
    std::fs::metadata(path)
        .is_ok_and(|meta| meta.is_file() && meta.permissions().mode() & 0o111 != 0)
}
