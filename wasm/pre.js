// Runs inside the module factory, before the generated glue.
// The heap limit (wasm/CMakeLists.txt, CRESTLINE_WASM_MAX_MEMORY): beyond it
// Session methods return {error: "mesh too large for the browser (N triangles)"}.
Module['maxMemoryBytes'] = 2147483648;
// Session methods return {error, kind} instead of throwing; callers that
// prefer exceptions wrap a result in check().
Module['check'] = function (result) {
  if (result && result.error) {
    var error = new Error(result.error);
    error.kind = result.kind;
    throw error;
  }
  return result;
};
