// Records every uncaught error, unhandled rejection and console.error into #errors (text
// and data-count) and the html element's data-errors, so a headless browser's DOM dump shows them.
window.reportErrors = [];
window.recordError = function (message) {
  window.reportErrors.push(String(message));
  document.documentElement.dataset.errors = String(window.reportErrors.length);
  var box = document.getElementById("errors");
  if (box) {
    box.textContent = window.reportErrors.join("\n");
    box.dataset.count = String(window.reportErrors.length);
  }
};
window.onerror = function (message, source, line, column) {
  window.recordError(message + " (line " + line + ":" + column + ")");
};
window.addEventListener("unhandledrejection", function (event) {
  window.recordError("unhandled rejection: " + event.reason);
});
(function () {
  var original = console.error;
  console.error = function () {
    window.recordError(Array.prototype.join.call(arguments, " "));
    original.apply(console, arguments);
  };
})();
