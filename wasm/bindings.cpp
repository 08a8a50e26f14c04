// Embind declarations only; the conversions live in session.cpp.
#include <emscripten/bind.h>

#include "crestline/numerics/parallel.h"
#include "session.h"

EMSCRIPTEN_BINDINGS(crestline) {
  // Threads the pipeline uses: 1 in the plain build; in crestline-mt,
  // Module.threadCount once pre-threads.js has called setThreads.
  emscripten::function("threads", &crestline::max_threads);
  emscripten::function("setThreads", &crestline::set_max_threads);
  using crestline::wasm::Session;
  emscripten::class_<Session>("Session")
      .constructor<>()
      .function("load", &Session::load)
      .function("loadFile", &Session::loadFile)
      .function("setOptions", &Session::setOptions)
      .function("options", &Session::options)
      .function("describe", &Session::describe)
      .function("run", &Session::run)
      .function("surface", &Session::surface)
      .function("lines", &Session::lines)
      .function("keptLines", &Session::keptLines)
      .function("creases", &Session::creases)
      .function("fields", &Session::fields)
      .function("stats", &Session::stats)
      .function("linesObj", &Session::linesObj)
      .function("linesJson", &Session::linesJson)
      .function("statsJson", &Session::statsJson)
      .function("linesSvg", &Session::linesSvg)
      .function("linesGlb", &Session::linesGlb);
}
