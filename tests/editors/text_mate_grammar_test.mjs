// The editors' grammar in a real TextMate engine: vscode-textmate with the Oniguruma
// regular expressions VS Code uses (vscode-oniguruma, WebAssembly) loads the grammar
// `ontogen help --grammar` prints, tokenizes a model and a few lines, and the scopes of
// known tokens are checked: a directive, its word, a number, comments, a string, turtle,
// music and creature commands, keywords, a built-in function and a constant.
//
//   node text_mate_grammar_test.mjs ONTOGEN_EXECUTABLE SOURCE_DIR
// Exit 0: passed; 1: failed; 77: a checker is missing (a failure when CI=true).

import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const [executable, sourceDir] = process.argv.slice(2);
const ci = process.env.CI === 'true';
const require = createRequire(import.meta.url);

function missing(what) {
  console.error(`grammar test: ${what} is missing (bash .ci/setup --checkers installs it)`);
  process.exit(ci ? 1 : 77);
}
let textmate, oniguruma;
try {
  textmate = require('vscode-textmate');
  oniguruma = require('vscode-oniguruma');
} catch {
  missing('vscode-textmate or vscode-oniguruma (NODE_PATH=.tools/node_modules)');
}

let failures = 0;
function check(condition, message) {
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${message}`);
  if (!condition) failures += 1;
  return condition;
}

const printed = spawnSync(executable, ['help', '--grammar'], { encoding: 'utf8' });
check(printed.status === 0, `ontogen help --grammar exits 0 (${printed.stderr.trim()})`);
const grammarText = printed.stdout;
check(grammarText === fs.readFileSync(path.join(sourceDir, 'editors/vscode/syntaxes/cell.tmLanguage.json'), 'utf8'),
      'the committed grammar is what ontogen help --grammar prints');

const wasm = fs.readFileSync(path.join(path.dirname(require.resolve('vscode-oniguruma')), 'onig.wasm'));
await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
const registry = new textmate.Registry({
  onigLib: Promise.resolve({
    createOnigScanner: (patterns) => new oniguruma.OnigScanner(patterns),
    createOnigString: (s) => new oniguruma.OnigString(s),
  }),
  loadGrammar: async (scope) =>
    scope === 'source.cell' ? textmate.parseRawGrammar(grammarText, 'cell.tmLanguage.json') : null,
});
const grammar = await registry.loadGrammar('source.cell');
if (!check(grammar !== null, 'the grammar loads')) process.exit(1);

// Every token of a text: [text, scopes] line by line.
function tokenize(text) {
  const tokens = [];
  let state = textmate.INITIAL;
  for (const line of text.split('\n')) {
    const result = grammar.tokenizeLine(line, state);
    for (const token of result.tokens)
      tokens.push({ text: line.substring(token.startIndex, token.endIndex), scopes: token.scopes });
    state = result.ruleStack;
  }
  return tokens;
}

// The first token whose text is `text` (after `after`, if given) has `scope` innermost.
function expectScope(tokens, text, scope, after = 0) {
  const token = tokens.slice(after).find((t) => t.text === text);
  const got = token ? token.scopes[token.scopes.length - 1] : '(no such token)';
  check(got === scope, `'${text}' is ${scope} (got ${got})`);
}

const piston = tokenize(fs.readFileSync(path.join(sourceDir, 'models/piston.cell'), 'utf8'));
check(piston.length > 300, `models/piston.cell tokenizes (${piston.length} tokens)`);
expectScope(piston, '// The piston and flywheel of paper 000 (McCormack 2004), Fig. 5, typed in as printed.',
            'comment.line.double-slash.cell');
expectScope(piston, 'lsystem', 'storage.type.cell');
expectScope(piston, '#define', 'keyword.control.directive.cell');
expectScope(piston, 'WR', 'entity.name.constant.cell');
expectScope(piston, '50', 'constant.numeric.cell');
expectScope(piston, '0.04', 'constant.numeric.cell');
expectScope(piston, '#radians', 'keyword.control.directive.cell');
expectScope(piston, '#music', 'keyword.control.directive.cell');
expectScope(piston, 'developmental', 'constant.language.cell');
expectScope(piston, 'axiom', 'keyword.control.cell');
expectScope(piston, 'equiv', 'keyword.control.cell');
expectScope(piston, 'cC', 'support.function.turtle.cell');
expectScope(piston, 'disc', 'support.function.turtle.cell');
expectScope(piston, '->', 'keyword.operator.arrow.cell');
expectScope(piston, 'interpret', 'keyword.control.cell');
expectScope(piston, 'program', 'support.function.music.cell');
expectScope(piston, 'modulation', 'support.function.music.cell');
expectScope(piston, 'minor', 'constant.language.scale.cell');
expectScope(piston, 'cos', 'support.function.builtin.cell');
expectScope(piston, 'pi', 'constant.language.cell');
expectScope(piston, 'age', 'variable.language.cell');
expectScope(piston, 'g', 'keyword.control.cell');

const text = [
  '/* a block comment',
  '   over two lines */ axiom',
  '#surface 1 "bud.obj"',
  'cell Leg(g = 2) { interpret creature { hip(0.5, 1, 1, 1.5, 0) knee foot } }',
  'cell Body { interpret dynamics { servo(5000, 100) wind(2, 0, 0) } }',
  '#colour 3',
];
const lines = tokenize(text.join('\n'));
// The scopes of the character at `column` of line `row`, innermost last.
function scopesAt(row, column) {
  let state = textmate.INITIAL;
  for (let i = 0; i < row; ++i) state = grammar.tokenizeLine(text[i], state).ruleStack;
  const token = grammar.tokenizeLine(text[row], state).tokens.find((t) => t.startIndex <= column && column < t.endIndex);
  return token ? token.scopes : [];
}
function expectScopeAt(row, column, scope, what) {
  const scopes = scopesAt(row, column);
  check(scopes.includes(scope), `${what} is in ${scope} (got ${scopes.join(' ')})`);
}
expectScopeAt(0, 10, 'comment.block.cell', "a block comment's first line");
expectScopeAt(1, 5, 'comment.block.cell', "a block comment's second line");
expectScopeAt(1, 22, 'keyword.control.cell', "'axiom' after the comment's end");
expectScope(lines, '"bud.obj"', 'string.quoted.double.cell');
expectScope(lines, 'cell', 'storage.type.cell');
// A parameter named g is a name, not the keyword g.
check(!scopesAt(3, 9).includes('keyword.control.cell'), `the parameter g is no keyword (got ${scopesAt(3, 9).join(' ')})`);
expectScope(lines, 'hip', 'support.function.creature.cell');
expectScope(lines, 'knee', 'support.function.creature.cell');
expectScope(lines, 'servo', 'support.function.dynamics.cell');
expectScope(lines, 'wind', 'support.function.dynamics.cell');
expectScope(lines, '#colour', 'invalid.illegal.directive.cell');

console.log(failures === 0 ? 'grammar test: passed' : `grammar test: ${failures} failed`);
process.exit(failures === 0 ? 0 : 1);
