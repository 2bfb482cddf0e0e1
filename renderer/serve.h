// `render --serve`: one long-lived process that renders request after request, so that a caller pays for
// the process, the thread pool and the first touch of memory once, not per render.
#pragma once

namespace mcval {

/// Writes the greeting line "mcval-serve 1" on stdout, then reads requests on stdin until it ends; each is a `render` command's arguments, framed as a line with
/// their count, then per argument a line with its length in bytes and those bytes. Runs each as
/// runRenderCommand and answers on stdout with one line: the command's exit status. Anything else the
/// commands print goes to stderr, so it cannot be taken for an answer. Returns 0 at the end of the
/// input, 3 on a request it cannot read (its reason on stderr).
int serveRenderRequests();

}  // namespace mcval
