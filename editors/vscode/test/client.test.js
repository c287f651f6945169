// The extension's client, run in plain Node with `vscode` and the language client replaced by
// recorders: activation starts `patina lsp` over stdio for the `patina` language, the settings
// change the command, and a server that cannot start is reported, not thrown.
'use strict';

const assert = require('node:assert/strict');
const Module = require('node:module');
const path = require('node:path');
const test = require('node:test');

/** What the stand-ins saw. */
const seen = { clients: [], errors: [], commands: [], settings: {} };
let failStart = false;

const vscode = {
  workspace: {
    getConfiguration: (section) => ({
      get: (key, fallback) => (`${section}.${key}` in seen.settings ? seen.settings[`${section}.${key}`] : fallback),
    }),
    onDidChangeConfiguration: () => ({ dispose() {} }),
  },
  window: {
    showErrorMessage: async (message) => {
      seen.errors.push(message);
      return undefined;
    },
  },
  commands: {
    registerCommand: (name) => {
      seen.commands.push(name);
      return { dispose() {} };
    },
    executeCommand: async () => undefined,
  },
};

class LanguageClient {
  constructor(id, name, serverOptions, clientOptions) {
    Object.assign(this, { id, name, serverOptions, clientOptions, running: false });
    seen.clients.push(this);
  }
  async start() {
    if (failStart) throw new Error('spawn patina ENOENT');
    this.running = true;
  }
  async stop() {
    this.running = false;
  }
}
const languageClient = { LanguageClient, TransportKind: { stdio: 0, ipc: 1 } };

const load = Module._load;
Module._load = function (request, ...rest) {
  if (request === 'vscode') return vscode;
  if (request === 'vscode-languageclient/node') return languageClient;
  return load.call(this, request, ...rest);
};
const extension = require(path.join(__dirname, '..', 'src', 'extension.js'));

const context = () => ({ subscriptions: [] });

test('activation starts `patina lsp` over stdio for the patina language', async () => {
  seen.clients.length = 0;
  await extension.activate(context());
  const client = seen.clients.at(-1);
  assert.equal(client.id, 'patina');
  assert.deepEqual(client.serverOptions, { command: 'patina', args: ['lsp'], transport: 0 });
  assert.deepEqual(
    client.clientOptions.documentSelector.map((s) => s.language),
    ['patina', 'patina'],
  );
  assert.ok(client.running);
  assert.ok(seen.commands.includes('patina.restartServer'));
  await extension.deactivate();
  assert.ok(!client.running);
});

test('patina.serverPath and patina.serverArgs make the command', async () => {
  seen.settings = { 'patina.serverPath': ' /opt/patina/bin/patina ', 'patina.serverArgs': ['lsp', '-I', 'include'] };
  await extension.activate(context());
  assert.deepEqual(seen.clients.at(-1).serverOptions.args, ['lsp', '-I', 'include']);
  assert.equal(seen.clients.at(-1).serverOptions.command, '/opt/patina/bin/patina');
  await extension.deactivate();
  // An empty path falls back to `patina` on PATH.
  assert.deepEqual(extension.serverCommand(vscode.workspace.getConfiguration('x')), { command: 'patina', args: ['lsp'] });
  seen.settings = { 'patina.serverPath': '' };
  assert.equal(extension.serverCommand(vscode.workspace.getConfiguration('patina')).command, 'patina');
  seen.settings = {};
});

test('a server that cannot start is an error message, not an exception', async () => {
  failStart = true;
  seen.errors.length = 0;
  await extension.activate(context());
  failStart = false;
  assert.equal(seen.errors.length, 1);
  assert.match(seen.errors[0], /could not start the language server `patina lsp`: spawn patina ENOENT/);
  assert.match(seen.errors[0], /patina\.serverPath/);
  await extension.deactivate();
});

test('the manifest contributes the language, grammar and settings the client reads', () => {
  const manifest = require(path.join(__dirname, '..', 'package.json'));
  const language = manifest.contributes.languages.find((l) => l.id === 'patina');
  assert.deepEqual(language.extensions, ['.sl']);
  assert.equal(manifest.contributes.grammars[0].language, 'patina');
  const settings = manifest.contributes.configuration.properties;
  assert.equal(settings['patina.serverPath'].default, 'patina');
  assert.deepEqual(settings['patina.serverArgs'].default, ['lsp']);
});
