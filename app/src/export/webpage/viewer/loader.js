// Starts the page: inflates the inlined JavaScript modules (three.js and the viewer), links them
// through blob: URLs (a page opened from disk can fetch nothing, and a module made from memory
// cannot resolve relative imports, so each `cutaway-module:<name>` import names a module made
// before it) and runs the viewer, which inflates the scenes as it needs them.
(function () {
  'use strict';
  var PAYLOAD = 'script[type="application/x-cutaway-gzip-base64"]';

  function bytesOf(element) {
    var binary = atob(element.textContent);
    var bytes = new Uint8Array(binary.length);
    for (var i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    return bytes;
  }

  function inflate(element) {
    var stream = new Blob([bytesOf(element)]).stream().pipeThrough(new DecompressionStream('gzip'));
    return new Response(stream).arrayBuffer().then(function (buffer) {
      return new Uint8Array(buffer);
    });
  }

  function fail(error) {
    console.error(error);
    var status = document.getElementById('cutaway-status');
    status.hidden = false;
    status.className = 'error';
    status.textContent = 'This page could not start: ' + (error && error.message ? error.message : error);
    document.body.dataset.state = 'failed';
  }

  async function start() {
    if (typeof DecompressionStream === 'undefined' || !window.WebGLRenderingContext) {
      throw new Error('this browser lacks WebGL or DecompressionStream; open the page in a current Chrome, Edge, Firefox or Safari');
    }
    var elements = Array.prototype.slice.call(document.querySelectorAll(PAYLOAD + '[data-module]'));
    var texts = await Promise.all(elements.map(function (element) {
      return inflate(element).then(function (bytes) {
        return new TextDecoder().decode(bytes);
      });
    }));
    var urls = {};
    elements.forEach(function (element, k) {
      var name = element.dataset.module;
      var text = texts[k].replace(/'cutaway-module:([^']+)'/g, function (_, dependency) {
        if (!Object.prototype.hasOwnProperty.call(urls, dependency)) {
          throw new Error(name + ' imports ' + dependency + ', which is not loaded before it');
        }
        return "'" + urls[dependency] + "'";
      });
      urls[name] = URL.createObjectURL(new Blob([text], { type: 'text/javascript' }));
    });
    var main = await import(urls['main.js']);
    await main.start({
      scene: function (k) {
        var element = document.getElementById('cutaway-scene-' + k);
        if (!element) return Promise.reject(new Error('the page holds no scene ' + k));
        return inflate(element);
      },
    });
  }

  start().catch(fail);
})();
