"""A generated block of a document: the lines between two marker lines, which a script writes
(--write) or checks against what it would write (--check). Shared by the scripts that keep
numbers and tables of docs/ regenerated (bundled_verdicts, doc_tolerance,
layout_table)."""
import argparse
import sys


def WriteOrCheck(description, extra=None):
    """The scripts' command line: exactly one of --write and --check; `extra(parser)` adds more."""
    p = argparse.ArgumentParser(description=description)
    if extra:
        extra(p)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--write", action="store_true")
    g.add_argument("--check", action="store_true")
    return p.parse_args()


class Block:
    """The block of `doc` (a pathlib.Path) between the lines `begin` and `end`."""

    def __init__(self, doc, begin, end, script):
        text = doc.read_text()
        if begin not in text or end not in text:
            sys.exit("%s: %s: the markers of the generated block are missing (%s, %s)"
                     % (script, doc, begin, end))
        self.doc, self.begin, self.end = doc, begin, end
        self.head, rest = text.split(begin, 1)
        self.old, self.tail = rest.split(end, 1)

    def Write(self, new):
        """Replaces the block by `new` (without its markers)."""
        self.doc.write_text(self.head + self.begin + "\n" + new + "\n" + self.end + self.tail)
