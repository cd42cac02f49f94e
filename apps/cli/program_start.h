#pragma once
/// @file
/// How the `needle` program starts, before any command parses its options: two hand-overs to
/// another process image (execv), each for speed, neither changing what a command computes.

namespace needle {

/// A file argument of 4 MiB or more (a dense lift table): the program starts itself again with
/// GLIBC_TUNABLES=glibc.malloc.hugetlb=1, glibc's heap in transparent huge pages, once (the
/// restarted program unsets it, and its mark, before any child). Returns at once otherwise:
/// GLIBC_TUNABLES set by the user, a privileged run, /proc/self/exe not needle (valgrind, the
/// dynamic loader), or a failed exec (the run goes on as it is). glibc only; a no-op elsewhere.
void RestartWithHugePages(int argc, char** argv);

/// `needle fit` and `needle serve`: runs needle-fit-serve with the same arguments, found beside
/// this program (the build tree), else in libexec/needle (an install). Returns only when neither
/// could be started, having printed one line: exit 3 (an installation's fault).
int RunInFitServe(char** argv);

}  // namespace needle
