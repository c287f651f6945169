// @ts-check
// The Patina extension: the language (highlighting comes from syntaxes/) and a client for the
// language server `patina lsp`, started over standard input and output.
'use strict';

const vscode = require('vscode');
const { LanguageClient, TransportKind } = require('vscode-languageclient/node');

/** @type {LanguageClient | undefined} */
let client;

/**
 * The command that runs the server, from the settings `patina.serverPath` and `patina.serverArgs`.
 * @param {{ get<T>(section: string, defaultValue: T): T }} config the `patina` section
 * @returns {{ command: string, args: string[] }}
 */
function serverCommand(config) {
  const path = config.get('serverPath', 'patina');
  const args = config.get('serverArgs', ['lsp']);
  return {
    command: typeof path === 'string' && path.trim() !== '' ? path.trim() : 'patina',
    args: Array.isArray(args) ? args.map(String) : ['lsp'],
  };
}

/** Starts the client, reporting a server that cannot be started. */
async function start() {
  const { command, args } = serverCommand(vscode.workspace.getConfiguration('patina'));
  /** @type {import('vscode-languageclient/node').ServerOptions} */
  const serverOptions = { command, args, transport: TransportKind.stdio };
  /** @type {import('vscode-languageclient/node').LanguageClientOptions} */
  const clientOptions = {
    documentSelector: [
      { scheme: 'file', language: 'patina' },
      { scheme: 'untitled', language: 'patina' },
    ],
  };
  client = new LanguageClient('patina', 'Patina Language Server', serverOptions, clientOptions);
  try {
    await client.start();
  } catch (error) {
    const message = error instanceof Error ? error.message : String(error);
    client = undefined;
    const choice = await vscode.window.showErrorMessage(
      `Patina: could not start the language server \`${[command, ...args].join(' ')}\`: ${message}. ` +
        'Set `patina.serverPath` to the `patina` command (it needs the `lsp` subcommand).',
      'Open Settings',
    );
    if (choice === 'Open Settings') {
      await vscode.commands.executeCommand('workbench.action.openSettings', 'patina.server');
    }
  }
}

/** Stops the client, if one runs. */
async function stop() {
  const running = client;
  client = undefined;
  if (running) {
    await running.stop();
  }
}

/** @param {vscode.ExtensionContext} context */
async function activate(context) {
  context.subscriptions.push(
    vscode.commands.registerCommand('patina.restartServer', async () => {
      await stop();
      await start();
    }),
    vscode.workspace.onDidChangeConfiguration(async (event) => {
      if (event.affectsConfiguration('patina.serverPath') || event.affectsConfiguration('patina.serverArgs')) {
        await stop();
        await start();
      }
    }),
    { dispose: () => void stop() },
  );
  await start();
}

function deactivate() {
  return stop();
}

module.exports = { activate, deactivate, serverCommand };
