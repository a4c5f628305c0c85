#!/usr/bin/env python3
"""Unit tests of msg_to_idl.py (the .msg -> plain IDL step of the Fast DDS interop test)."""

import pathlib
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import msg_to_idl  # noqa: E402  (imported from this folder)


class MsgToIdlTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = pathlib.Path(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def package(self, name, messages):
        folder = self.root / name / "msg"
        folder.mkdir(parents=True)
        for msg_name, text in messages.items():
            (folder / f"{msg_name}.msg").write_text(text, encoding="utf-8")
        return self.root / name

    def generate(self, *packages):
        out = self.root / "out.idl"
        status = msg_to_idl.main(["--out", str(out)] + [str(p) for p in packages])
        return status, out.read_text(encoding="utf-8") if out.exists() else ""

    def test_maps_types_bounds_and_constants_as_rosidl_does(self):
        pkg = self.package("pkg", {
            "Cmd": 'string ACTION_GO="go" # a comment with a "quote"\n'
                   "uint8 LEVEL=3\n"
                   "string<=64 action   # bounded\n"
                   "float32 speed 1.5\n"          # a default value: not on the wire
                   "string<=191[<=16] errors\n"
                   "int32[] counts\n"
                   "float64[3] xyz\n",
        })
        status, idl = self.generate(pkg)
        self.assertEqual(status, 0)
        self.assertIn('const string ACTION_GO = "go";', idl)
        self.assertIn("const uint8 LEVEL = 3;", idl)
        self.assertIn("string<64> action;", idl)
        self.assertIn("float speed;", idl)
        self.assertIn("sequence<string<191>, 16> errors;", idl)
        self.assertIn("sequence<int32> counts;", idl)
        self.assertIn("double xyz[3];", idl)
        self.assertNotIn("module dds_", idl, "fastddsgen -typeros2 adds dds_ itself")

    def test_a_used_type_comes_first_across_packages(self):
        base = self.package("builtin_interfaces", {"Time": "int32 sec\nuint32 nanosec\n"})
        pkg = self.package("pkg", {
            "A": "B b\nbuiltin_interfaces/Time stamp\n",
            "B": "bool ok\n",
        })
        status, idl = self.generate(base, pkg)
        self.assertEqual(status, 0)
        self.assertLess(idl.index("struct Time"), idl.index("struct A"))
        self.assertLess(idl.index("struct B"), idl.index("struct A"))
        self.assertIn("pkg::msg::B b;", idl)
        self.assertIn("builtin_interfaces::msg::Time stamp;", idl)

    def test_types_selects_the_named_messages_and_what_they_use(self):
        pkg = self.package("pkg", {"A": "B b\n", "B": "bool ok\n", "C": "bool other\n"})
        out = self.root / "out.idl"
        self.assertEqual(msg_to_idl.main(["--out", str(out), "--types", "pkg/A", str(pkg)]), 0)
        idl = out.read_text(encoding="utf-8")
        self.assertIn("struct A", idl)
        self.assertIn("struct B", idl)
        self.assertNotIn("struct C", idl)
        self.assertEqual(msg_to_idl.main(["--out", str(out), "--types", "pkg/Nope", str(pkg)]), 1)

    def test_an_empty_message_gets_rosidl_placeholder_member(self):
        status, idl = self.generate(self.package("pkg", {"Empty": "# nothing\n"}))
        self.assertEqual(status, 0)
        self.assertIn("uint8 structure_needs_at_least_one_member;", idl)

    def test_an_idl_keyword_as_field_name_is_escaped(self):
        status, idl = self.generate(self.package("pkg", {"K": "bool module\n"}))
        self.assertEqual(status, 0)
        self.assertIn("boolean _module;", idl)

    def test_bad_input_is_refused_naming_file_and_line(self):
        cases = {
            "unknown type": "Missing thing\n",
            "no name": "bool\n",
            "bound on a non-string": "int32<=4 x\n",
            "bad name": "bool 9lives\n",
            "self-containing": "Self me\n",
        }
        for label, text in cases.items():
            with self.subTest(label):
                folder = self.root / label.replace(" ", "_")
                (folder / "msg").mkdir(parents=True)
                (folder / "msg" / "Self.msg").write_text(text, encoding="utf-8")
                status, _ = self.generate(folder)
                self.assertEqual(status, 1, label)

    def test_a_package_without_messages_is_refused(self):
        (self.root / "empty" / "msg").mkdir(parents=True)
        status, _ = self.generate(self.root / "empty")
        self.assertEqual(status, 1)


if __name__ == "__main__":
    unittest.main()
