#!/usr/bin/python3
"""Unpack a GPU campaign's tarball (scripts/gpu_campaign.sh run) into DIR, trusting nothing in it: it
comes back from a borrowed machine.

usage: /usr/bin/python3 scripts/campaign_unpack.py TARBALL DIR        exit 0: unpacked; 1: refused

Every member is checked before anything is written, and one bad member refuses the whole tarball,
naming it and why. Allowed: the folder itself, a folder per config (a plain name) and plain files in
those folders (plain names: letters, digits, '.', '_', '-', not starting with '.'). Refused: links,
devices, FIFOs, sparse or other special members, absolute or '..' paths, deeper paths, a file over
FILE_CAP bytes or a tarball over TOTAL_CAP bytes unpacked. Files are written 0644 and folders 0755
whatever the tarball says (no setuid, setgid or world-writable bits), owned by whoever unpacks;
each file through a temporary file renamed into place, never through a link already in DIR.
"""
import os
import re
import sys
import tarfile

FILE_CAP = 512 * 1024 * 1024   # one runs.csv, samples.csv or hit record file
TOTAL_CAP = 2 * 1024 * 1024 * 1024
NAME = re.compile(r"[A-Za-z0-9_-][A-Za-z0-9._-]*")


class Refused(Exception):
    pass


def parts_of(member: tarfile.TarInfo) -> list:
    """The member's path as plain names (the leading './' of `tar -C DIR .` dropped)."""
    path = member.name
    if path.startswith("/") or "\\" in path:
        raise Refused(f"{member.name!r}: an absolute or odd path")
    parts = [p for p in path.split("/") if p not in ("", ".")]
    for part in parts:
        if part == ".." or not NAME.fullmatch(part):
            raise Refused(f"{member.name!r}: {part!r} is not a plain name")
    if len(parts) > 2:
        raise Refused(f"{member.name!r}: deeper than CONFIG/FILE")
    return parts


def vet(members) -> list:
    """(parts, member) of every member worth writing, after every check passed."""
    total, plan = 0, []
    for member in members:
        parts = parts_of(member)
        if member.isdir():
            if len(parts) == 2:
                raise Refused(f"{member.name!r}: a folder inside a config's folder")
            plan.append((parts, member))
            continue
        if not member.isreg() or member.issparse():
            kind = ("a symbolic link" if member.issym() else "a hard link" if member.islnk() else
                    "a character device" if member.ischr() else "a block device" if member.isblk() else
                    "a FIFO" if member.isfifo() else "a sparse file" if member.issparse() else "a special member")
            raise Refused(f"{member.name!r}: {kind}")
        if len(parts) != 2:
            raise Refused(f"{member.name!r}: a file outside a config's folder")
        if member.size > FILE_CAP:
            raise Refused(f"{member.name!r}: {member.size} bytes, over the {FILE_CAP}-byte cap of a file")
        total += member.size
        if total > TOTAL_CAP:
            raise Refused(f"{member.name!r}: the tarball unpacks to over {TOTAL_CAP} bytes")
        plan.append((parts, member))
    return plan


def real_folder(path: str):
    """A folder at `path` (made 0755 if absent), never a link to one."""
    if os.path.islink(path):
        raise Refused(f"{path}: is a symbolic link; refusing to unpack through it")
    if not os.path.exists(path):
        os.mkdir(path, 0o755)
    elif not os.path.isdir(path):
        raise Refused(f"{path}: exists and is not a folder")


def write(archive: tarfile.TarFile, member: tarfile.TarInfo, target: str):
    """The member's bytes into `target` through a temporary file beside it, 0644, renamed over."""
    source = archive.extractfile(member)
    temporary = f"{target}.unpack-{os.getpid()}.tmp"
    fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o644)
    try:
        with os.fdopen(fd, "wb") as out:
            left = member.size
            while left > 0:
                chunk = source.read(min(left, 1 << 20))
                if not chunk:
                    raise Refused(f"{member.name!r}: the tarball ends inside it")
                out.write(chunk)
                left -= len(chunk)
        os.chmod(temporary, 0o644)
        os.replace(temporary, target)
    except BaseException:
        if os.path.lexists(temporary):
            os.unlink(temporary)
        raise


def unpack(tarball: str, folder: str) -> list:
    with tarfile.open(tarball, "r:*") as archive:
        plan = vet(archive.getmembers())
        real_folder(folder)
        written = []
        for parts, member in plan:
            if not parts:
                continue
            real_folder(os.path.join(folder, parts[0]))
            if member.isdir():
                continue
            write(archive, member, os.path.join(folder, *parts))
            written.append("/".join(parts))
        return written


def main(args) -> int:
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    tarball, folder = args
    try:
        written = unpack(tarball, folder)
    except Refused as e:
        print(f"campaign_unpack: {tarball}: refused: {e}", file=sys.stderr)
        return 1
    except (OSError, tarfile.TarError, EOFError) as e:
        print(f"campaign_unpack: {tarball}: {e}", file=sys.stderr)
        return 1
    print(f"{folder}: {len(written)} file(s) unpacked")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
