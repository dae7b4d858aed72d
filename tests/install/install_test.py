#!/usr/bin/env python3
"""Tumble installed as a user installs it (issue 54): the Debian package built, installed with
apt-get, used from another folder, then removed.

  0. cmake --install into a prefix of the test's own: its tumble uses that prefix's mesh reader.
  1. cpack makes tumble_VERSION_ARCH.deb from the build (into a folder of the test's own);
     lintian finds no error in it; its Depends name Qt and its Suggests blender, slurm-wlm
     and ffmpeg.
  2. apt-get installs it (its dependencies are already on the machine).
  3. From an empty folder, with the build tree out of PATH:
     - tumble --version names the build's version and commit;
     - tumble --headless on an installed sample writes a glTF binary; a sample with meshes
       runs with the installed mesh reader (/usr/libexec/tumble, seen with strace);
     - tumble sweep on an installed sample writes its summary;
     - desktop-file-validate passes the desktop entry; xdg-mime takes a scene file (by its
       name *.tumble.json, or a sample's *.json by its content) as application/x-tumble-scene,
       plain JSON as application/json, and opens scenes with tumble.desktop;
     - the icons are PNGs of their folder's size; the man page has the version;
     - the editor from /usr/bin/tumble, on the display ctest runs under: it opens an
       installed sample given on its command line, File > Samples opens the first sample
       and the installed ones with meshes are in that menu, Help > Manual opens the manual.
  4. apt-get removes it: /usr/bin/tumble is gone.

Usage: install_test.py BUILD_DIR   (as root, or with sudo that asks no password)
"""
import gzip
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import time

BUILD = os.path.abspath(sys.argv[1])
SUDO = [] if os.geteuid() == 0 else ["sudo", "-n"]
EDITORS = []


def fail(message):
    print("FAIL:", message)
    for p in EDITORS:
        p.kill()
    sys.exit(1)


def run(cmd, cwd=None, env=None, check=True, timeout=600):
    r = subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=timeout)
    if check and r.returncode != 0:
        fail("%s exited with %d:\n%s\n%s" % (" ".join(cmd), r.returncode, r.stdout[-3000:], r.stderr[-3000:]))
    return r


def apt(*args):
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    return run(SUDO + ["apt-get", "-y", "-q", "--no-install-recommends"] + list(args), env=env)


def wait_for(what, check, timeout=90.0):
    end = time.time() + timeout
    while time.time() < end:
        value = check()
        if value:
            return value
        time.sleep(0.2)
    fail("timed out waiting for " + what)


def windows(name):
    r = run(["xdotool", "search", "--name", name], check=False)
    return r.stdout.split()


def title(window):
    return run(["xdotool", "getwindowname", window], check=False).stdout.strip()


def through_menus(window, sequence, what, done):
    """Opens the File menu with a click on it (the menu bar's first entry, at the window's top
    left) and types `sequence` into the open menus, until `done`; three tries. (Keys sent to
    the window itself were now and then lost with no window manager to give it focus: a
    lost Alt+F then sent the rest to the window.)"""
    for attempt in range(3):
        run(["xdotool", "key", "Escape"], check=False)  # a menu or dialog a lost key left open
        time.sleep(0.5)
        run(["xdotool", "mousemove", "--window", window, "20", "10", "click", "1"])
        time.sleep(1.0)
        for k in sequence:
            run(["xdotool", "key", k])
            time.sleep(0.6)
        end = time.time() + 20
        while time.time() < end:
            if done():
                return
            time.sleep(0.2)
    fail("timed out waiting for %s after File then %s three times" % (what, " ".join(sequence)))


def main():
    if SUDO and run(["sudo", "-n", "true"], check=False).returncode != 0:
        fail("the install test installs a package: run it as root or with sudo that asks no password")
    if not os.environ.get("DISPLAY"):
        fail("no DISPLAY: the install test opens the installed editor (./dev.sh test runs it under Xvfb)")
    out = tempfile.mkdtemp(prefix="tumble-install-")
    try:
        check_prefix(out)
        package = build_package(out)
        apt("install", package)
        try:
            check_installed(out)
        finally:
            apt("purge", "tumble")
        if os.path.exists("/usr/bin/tumble"):
            fail("/usr/bin/tumble is still there after apt-get purge tumble")
    finally:
        shutil.rmtree(out, ignore_errors=True)
    print("PASS")


def check_prefix(out):
    """`cmake --install` into a prefix of its own: the program there finds its mesh reader in
    that prefix's libexec/tumble, not the build tree's."""
    prefix = os.path.join(out, "prefix")
    run(["cmake", "--install", BUILD, "--prefix", prefix])
    tumble = os.path.join(prefix, "bin", "tumble")
    trace = os.path.join(out, "prefix-trace")
    work = os.path.join(out, "prefix-work")
    os.makedirs(work)
    env = dict(os.environ)
    env.pop("TUMBLE_MESH_READER", None)
    run(["strace", "-f", "-e", "trace=execve", "-o", trace, tumble, "--headless",
         os.path.join(prefix, "share", "tumble", "scenes", "mesh-shapes.json"), "--duration", "0.05", "--out", "m.csv",
         "--quiet"], cwd=work, env=env)
    with open(trace) as f:
        started = re.findall(r'execve\("([^"]+)"', f.read())
    reader = os.path.join(prefix, "libexec", "tumble", "tumble-mesh-reader")
    if reader not in started:
        fail("%s did not start %s; programs started: %s" % (tumble, reader, started))
    shutil.rmtree(prefix)


def build_package(out):
    run(["cpack", "--config", os.path.join(BUILD, "CPackConfig.cmake"), "-B", out], cwd=out)
    debs = [f for f in os.listdir(out) if re.fullmatch(r"tumble_\d+\.\d+\.\d+_[a-z0-9]+\.deb", f)]
    if len(debs) != 1:
        fail("cpack made %s, not one tumble_VERSION_ARCH.deb" % os.listdir(out))
    package = os.path.join(out, debs[0])
    lint = run(["lintian", "--tag-display-limit", "0", package], check=False)
    errors = [line for line in lint.stdout.splitlines() if line.startswith("E:")]
    if errors or lint.returncode not in (0, 2):
        fail("lintian:\n" + lint.stdout + lint.stderr)
    fields = run(["dpkg-deb", "-f", package, "Depends", "Suggests"]).stdout
    for needed in ("libqt6widgets6", "libqt63drender6", "libassimp5", "qt6-qpa-plugins"):
        if needed not in fields:
            fail("the package's Depends lack %s:\n%s" % (needed, fields))
    if not re.search(r"Suggests: .*blender.*slurm-wlm.*ffmpeg", fields):
        fail("the package's Suggests:\n" + fields)
    return package


def check_installed(out):
    home = os.path.join(out, "home")
    work = os.path.join(out, "work")
    os.makedirs(home)
    os.makedirs(work)
    # The build tree out of the way: only the installed program and its files.
    env = dict(os.environ, HOME=home, XDG_CONFIG_HOME=os.path.join(home, ".config"),
               PATH="/usr/local/bin:/usr/bin:/bin")
    env.pop("TUMBLE_MESH_READER", None)
    scenes = "/usr/share/tumble/scenes"

    built = run([os.path.join(BUILD, "app", "tumble"), "--version"]).stdout
    installed = run(["tumble", "--version"], cwd=work, env=env).stdout
    if installed != built or not re.fullmatch(r"tumble \d+\.\d+\.\d+ \(commit \S+\)\n", installed):
        fail("installed tumble --version says %r; the build says %r" % (installed, built))

    run(["tumble", "--headless", scenes + "/newtons-cradle.json", "--out", "cradle.glb", "--quiet"], cwd=work, env=env)
    with open(os.path.join(work, "cradle.glb"), "rb") as f:
        magic, version = struct.unpack("<4sI", f.read(8))
    if magic != b"glTF" or version != 2:
        fail("cradle.glb is not a glTF 2.0 binary")
    trace = os.path.join(out, "trace")
    run(["strace", "-f", "-e", "trace=execve", "-o", trace, "tumble", "--headless", scenes + "/mesh-shapes.json",
         "--duration", "0.05", "--out", "meshes.csv", "--quiet"], cwd=work, env=env)
    with open(trace) as f:
        started = re.findall(r'execve\("([^"]+)"', f.read())
    if "/usr/libexec/tumble/tumble-mesh-reader" not in started:
        fail("mesh-shapes.json's meshes were not read by the installed reader; programs started: %s" % started)

    run(["tumble", "sweep", scenes + "/bouncing-ball.json", "--vary", "ball.restitution=0.2:1:3", "--out", "sweep"],
        cwd=work, env=env)
    if not any(f.startswith("summary") for f in os.listdir(os.path.join(work, "sweep"))):
        fail("tumble sweep wrote no summary: %s" % os.listdir(os.path.join(work, "sweep")))

    desktop = "/usr/share/applications/tumble.desktop"
    r = run(["desktop-file-validate", desktop], check=False)
    if r.returncode != 0 or r.stdout.strip() or r.stderr.strip():
        fail("desktop-file-validate %s:\n%s%s" % (desktop, r.stdout, r.stderr))
    shutil.copy(scenes + "/newtons-cradle.json", os.path.join(work, "cradle.json"))
    shutil.copy(scenes + "/newtons-cradle.json", os.path.join(work, "cradle.tumble.json"))
    with open(os.path.join(work, "plain.json"), "w") as f:
        f.write('{"a": 1}\n')
    for name, want in (("cradle.json", "application/x-tumble-scene"), ("cradle.tumble.json", "application/x-tumble-scene"),
                       ("plain.json", "application/json")):
        got = run(["xdg-mime", "query", "filetype", name], cwd=work, env=env).stdout.strip()
        if got != want:
            fail("xdg-mime query filetype %s: %s, not %s" % (name, got, want))
    opener = run(["xdg-mime", "query", "default", "application/x-tumble-scene"], env=env).stdout.strip()
    if opener != "tumble.desktop":
        fail("scene files open with %r, not tumble.desktop" % opener)

    for size in (16, 24, 32, 48, 64, 128, 256):
        with open("/usr/share/icons/hicolor/%dx%d/apps/tumble.png" % (size, size), "rb") as f:
            head = f.read(24)
        if head[:8] != b"\x89PNG\r\n\x1a\n" or struct.unpack(">II", head[16:24]) != (size, size):
            fail("the %d px icon is not a %dx%d PNG" % (size, size, size))
    with gzip.open("/usr/share/man/man1/tumble.1.gz", "rt") as f:
        man = f.read()
    if ".SH NAME" not in man or built.strip() not in man:
        fail("the man page has no NAME section or not the version %r" % built.strip())

    check_editor(work, env)


def check_editor(work, env):
    editor = subprocess.Popen(["/usr/bin/tumble", "/usr/share/tumble/scenes/newtons-cradle.json"], cwd=work, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    EDITORS.append(editor)
    try:
        def main_window():
            for w in windows(" - Tumble$"):
                if title(w).startswith("newtons-cradle.json"):
                    return w
            if editor.poll() is not None:
                fail("the installed editor exited with %d: %s" % (editor.returncode, editor.stderr.read()[-2000:]))
            return None
        w = wait_for("the installed editor's window on newtons-cradle.json", main_window)
        # Help > Manual: from File, Left goes round to Help (the menu bar's last).
        through_menus(w, ["Left", "m"], "Help > Manual's window", lambda: windows("^Tumble Manual$"))
        for m in windows("^Tumble Manual$"):
            run(["xdotool", "windowfocus", "--sync", m], check=False)
            run(["xdotool", "key", "Escape"], check=False)
        wait_for("the manual to close", lambda: not windows("^Tumble Manual$"))
        # File > Samples, its first entry (the submenu opens on it).
        through_menus(w, ["s", "Return"], "File > Samples' first sample", lambda: title(w).startswith("tumbling-box.json"))
        # The installed samples with meshes are at the menu's end: the last one (Up from the
        # first) opens from its installed file (the window's title names it).
        through_menus(w, ["s", "Up", "Return"], "File > Samples' last sample (installed, with meshes)",
                      lambda: re.match(r"(mesh-shapes|mug-on-board)\.json", title(w)))
    finally:
        editor.terminate()
        try:
            editor.wait(timeout=20)
        except subprocess.TimeoutExpired:
            editor.kill()


if __name__ == "__main__":
    main()
