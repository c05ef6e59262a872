#!/usr/bin/python3
"""Tests of scripts/campaign_unpack.py on hostile tarballs made here (tarfile writes device, FIFO
and link members without root): each is refused whole, naming the member, and nothing is written;
a good tarball unpacks with our modes, and a link planted in DIR is replaced, never written through.

usage: /usr/bin/python3 scripts/test_campaign_unpack.py [-v]
"""
import io
import os
import stat
import sys
import tarfile
import tempfile
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import campaign_unpack  # noqa: E402


def tarball(path: Path, members):
    """A tar.xz of (TarInfo fields, bytes or None) members."""
    with tarfile.open(path, "w:xz") as archive:
        for fields, data in members:
            info = tarfile.TarInfo(fields.pop("name"))
            for key, value in fields.items():
                setattr(info, key, value)
            if data is not None:
                info.size = len(data)
            archive.addfile(info, io.BytesIO(data) if data is not None else None)


def plain(name, data=b"run,status\n000,ok\n", mode=0o644):
    return {"name": name, "mode": mode}, data


class Unpack(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory(prefix="test_campaign_unpack.")
        self.root = Path(self.tmp.name)
        self.out = self.root / "results"

    def tearDown(self):
        self.tmp.cleanup()

    def refused(self, members, why):
        tarball(self.root / "t.tar.xz", members)
        with self.assertRaises(campaign_unpack.Refused) as raised:
            campaign_unpack.unpack(str(self.root / "t.tar.xz"), str(self.out))
        self.assertIn(why, str(raised.exception))
        self.assertFalse(self.out.exists(), "nothing written before every member was checked")

    def test_a_good_tarball_unpacks_with_our_modes(self):
        members = [({"name": ".", "type": tarfile.DIRTYPE, "mode": 0o777}, None),
                   ({"name": "./bunny", "type": tarfile.DIRTYPE, "mode": 0o777}, None),
                   plain("./bunny/runs.csv", mode=0o6777), plain("./bunny/context.json", b"{}\n")]
        tarball(self.root / "t.tar.xz", members)
        written = campaign_unpack.unpack(str(self.root / "t.tar.xz"), str(self.out))
        self.assertEqual(sorted(written), ["bunny/context.json", "bunny/runs.csv"])
        runs = self.out / "bunny" / "runs.csv"
        self.assertEqual(runs.read_bytes(), b"run,status\n000,ok\n")
        self.assertEqual(stat.S_IMODE(runs.stat().st_mode), 0o644, "no setuid, setgid or world-writable bits")
        self.assertEqual(stat.S_IMODE((self.out / "bunny").stat().st_mode) & 0o022, 0)

    def test_special_members_are_refused(self):
        for kind, why in ((tarfile.CHRTYPE, "a character device"), (tarfile.BLKTYPE, "a block device"),
                          (tarfile.FIFOTYPE, "a FIFO")):
            with self.subTest(why=why):
                self.refused([plain("./bunny/runs.csv"), ({"name": "./bunny/null", "type": kind, "devmajor": 1,
                                                           "devminor": 3, "mode": 0o666}, None)], why)
        self.refused([({"name": "./bunny/passwd", "type": tarfile.SYMTYPE, "linkname": "/etc/passwd"}, None)],
                     "a symbolic link")
        self.refused([plain("./bunny/runs.csv"),
                      ({"name": "./bunny/samples.csv", "type": tarfile.LNKTYPE, "linkname": "./bunny/runs.csv"}, None)],
                     "a hard link")

    def test_paths_outside_the_layout_are_refused(self):
        self.refused([plain("/etc/cron.d/x")], "an absolute or odd path")
        self.refused([plain("./bunny/../../x")], "'..' is not a plain name")
        self.refused([plain("./bunny/deeper/runs.csv")], "deeper than CONFIG/FILE")
        self.refused([plain("./runs.csv")], "a file outside a config's folder")
        self.refused([plain("./bunny/.hidden")], "is not a plain name")

    def test_sizes_are_capped(self):
        cap = campaign_unpack.FILE_CAP
        campaign_unpack.FILE_CAP = 1000
        try:
            self.refused([plain("./bunny/samples.csv", b"0" * 1001)], "over the 1000-byte cap")
        finally:
            campaign_unpack.FILE_CAP = cap
        total = campaign_unpack.TOTAL_CAP
        campaign_unpack.TOTAL_CAP = 1500
        try:
            self.refused([plain("./bunny/a.csv", b"0" * 800), plain("./bunny/b.csv", b"0" * 800)], "over 1500 bytes")
        finally:
            campaign_unpack.TOTAL_CAP = total

    def test_a_link_planted_in_the_folder_is_replaced_not_written_through(self):
        victim = self.root / "victim"
        victim.write_text("keep\n")
        (self.out / "bunny").mkdir(parents=True)
        os.symlink(victim, self.out / "bunny" / "runs.csv")
        tarball(self.root / "t.tar.xz", [plain("./bunny/runs.csv")])
        campaign_unpack.unpack(str(self.root / "t.tar.xz"), str(self.out))
        self.assertEqual(victim.read_text(), "keep\n")
        self.assertFalse((self.out / "bunny" / "runs.csv").is_symlink())
        # A config folder that is a link: refused, nothing written through it.
        elsewhere = self.root / "elsewhere"
        elsewhere.mkdir()
        os.symlink(elsewhere, self.out / "raytypes")
        tarball(self.root / "u.tar.xz", [plain("./raytypes/runs.csv")])
        with self.assertRaises(campaign_unpack.Refused):
            campaign_unpack.unpack(str(self.root / "u.tar.xz"), str(self.out))
        self.assertEqual(list(elsewhere.iterdir()), [])

    def test_the_command_says_why_and_exits_1(self):
        tarball(self.root / "t.tar.xz", [({"name": "./bunny/zero", "type": tarfile.CHRTYPE, "devmajor": 1,
                                            "devminor": 5}, None)])
        err = io.StringIO()
        stderr, sys.stderr = sys.stderr, err
        try:
            rc = campaign_unpack.main([str(self.root / "t.tar.xz"), str(self.out)])
        finally:
            sys.stderr = stderr
        self.assertEqual(rc, 1)
        self.assertIn("refused: './bunny/zero': a character device", err.getvalue())


if __name__ == "__main__":
    unittest.main()
