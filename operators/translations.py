"""Japanese (ja_JP) translation of the add-on's interface, through ``bpy.app.translations``.

English stays the source and the default; Blender shows these strings when the interface
language is Japanese and "Translate Interface / Tooltips / New Data" are on.  The words are the
ones a Japanese shop floor uses (ボールエンドミル, ステップオーバー, 切込み深さ, ワーク原点, 展開図,
タレットパンチ, ニブリング, 彫刻刀跡 ...).

Lookup contexts: property names and descriptions, enum items, panel and menu labels, tooltips
and messages use the default context ``"*"``; operator labels (buttons, menus, F3 search) use
``"Operator"``, so every operator label is entered in both.

Messages: Blender translates labels and tooltips by itself, but not what Python reports or
raises.  Every report goes through :func:`translate_message`: fixed (whole-string) messages are
looked up with ``bpy.app.translations.pgettext_rpt`` (poll messages with ``pgettext_tip``);
messages built with f-strings (object names, counts, lengths) are matched against
:data:`MESSAGE_TEMPLATES`, English with ``{}`` where the f-string has a value, and the values are
put into the Japanese template's ``{0}``, ``{1}`` ... (word order differs).
"""
from __future__ import annotations

import re

import bpy

LOCALE = "ja_JP"
DEFAULT = "*"           # bpy.app.translations.contexts.default
OPERATOR = "Operator"   # bpy.app.translations.contexts.operator_default

# Operator labels (bl_label): entered in both the "Operator" and the default context.
OPERATOR_LABELS = {
    # simulate.py
    "Simulate": "シミュレーション",
    "Show Finding": "指摘箇所を表示",
    # preferences.py
    "Add Tool": "工具を追加",
    "Remove Tool": "工具を削除",
    "Use Library Tool": "ライブラリの工具を使用",
    # engrave.py
    "Generate Engraving": "彫刻パスを生成",
    "Export Engraving NC": "彫刻NCを書き出し",
    # rotary.py
    "Generate Rotary Pockets": "回転テーブルポケットを生成",
    "Export Rotary NC": "回転テーブルNCを書き出し",
    "Mark as Pocket": "ポケットに指定",
    # stepnc.py
    "Import ISO 14649": "ISO 14649を読み込み",
    "Generate Workplan Toolpaths": "ワークプランの工具経路を生成",
    "Export Workplan NC": "ワークプランのNCを書き出し",
    "Export ISO 14649": "ISO 14649で書き出し",
    "Move Workingstep": "ワーキングステップを移動",
    # turnmill.py
    "Classify Faces": "面を分類",
    "Generate Turn-Mill Paths": "複合加工の工具経路を生成",
    "Export Turn-Mill NC": "複合加工NCを書き出し",
    # carve.py
    "Generate Carving": "曲面加工パスを生成",
    "Export Carving NC": "曲面加工NCを書き出し",
    "Add Sample Design": "サンプル形状を追加",
    # sheetmetal.py
    "Unfold Twisted Quad": "ねじれ四辺形を展開",
    "Corners from Selected Face": "選択面から頂点を取得",
    "Import CADKEY CDL": "CADKEY CDLを読み込み",
    "Export Punch NC, DXF, SVG": "パンチNC・DXF・SVGを書き出し",
    "Pipe Elbow": "エビ管を作成",
    "Export Elbow Patterns": "エビ管の展開図を書き出し",
}

# Texts given to layout.operator(text=...): Blender looks them up in the operator's context.
OPERATOR_TEXTS = {
    "Import CDL": "CDLを読み込み",
    "From Selected Face": "選択面から取得",
    "CADKEY CDL (.cdl)": "CADKEY CDL (.cdl)",
    "ISO 14649 STEP-NC (.stp, .p21)": "ISO 14649 STEP-NC (.stp, .p21)",
    "ISO 14649 STEP-NC (.stp)": "ISO 14649 STEP-NC (.stp)",
    "Wave Relief": "波のレリーフ",
    "Domed Plate": "ドーム形の銘板",
    "Steep Ridge": "急斜面の尾根",
    "Walled Block": "壁のあるブロック",
    "Vertical Block": "垂直壁のブロック",
}

# Operator tooltips (the operator classes' docstrings).
OPERATOR_DESCRIPTIONS = {
    "Cut the stock with the job's toolpaths and check for gouges, rapids through material and moves outside "
    "the machine": "ジョブの工具経路で素材を削り、削り込み・材料内の早送り・機械のストローク外の移動を調べます",
    "Put the 3D cursor on a finding and centre the view on it": "指摘箇所に3Dカーソルを置き、ビューの中心に表示します",
    "Write the carving NC program for the chosen controller": "選んだ制御装置用に曲面加工のNCプログラムを書き出します",
    "Plan the Z-level roughing and the ball finishing raster over the design mesh, and show the toolpaths":
        "設計形状のメッシュに Z 等高線荒加工とボール仕上げの走査を計画し、工具経路を表示します",
    "Add a built-in design (a wave relief or a domed plate, in mm) and pick it as the design":
        "組み込みの形状（波のレリーフかドーム形の銘板、mm 単位）を追加し、設計形状に選びます",
    "Add a tool to the library": "工具ライブラリに工具を追加します",
    "Remove the selected tool from the library": "選択した工具を工具ライブラリから削除します",
    "Use a tool from the library for the engraving's roughing ball or finishing flat":
        "ライブラリの工具を、彫刻の荒加工用ボールエンドミルまたは仕上げ用フラットエンドミルに使います",
    "Plan the gouge-texture roughing, band finishing and burr contour, and show the toolpaths":
        "彫刻刀跡の荒加工、帯の仕上げ加工、バリ取り輪郭を計算し、工具経路を表示します",
    "Write the engraving NC program for the chosen controller":
        "選んだ制御装置向けに彫刻のNCプログラムを書き出します",
    "Plan the roughing, wall finishing and bottom spirals of every pocket, in C-X-Z":
        "すべてのポケットの荒加工・壁面仕上げ・底面スパイラルをC-X-Zで計算します",
    "Write the C-X-Z program for the wood lathe": "木工旋盤用のC-X-Zプログラムを書き出します",
    "Mark the selected outline objects as rotary pockets (or unmark them)":
        "選択した輪郭オブジェクトを回転テーブルのポケットに指定します（または指定を解除します）",
    "Import an ISO 14649 (STEP-NC) Part 21 file: stock, features and the workplan":
        "ISO 14649（STEP-NC）のPart 21ファイルを読み込みます：素材、フィーチャー、ワークプラン",
    "Convert the workplan, in the list's order, and show the toolpaths":
        "ワークプランをリストの順に変換し、工具経路を表示します",
    "Write the G-code of the workplan, in the list's order, without the switched-off workingsteps":
        "ワークプランのGコードをリストの順に書き出します（オフにしたワーキングステップは除きます）",
    "Write the pockets modelled in Blender as an ISO 14649 (STEP-NC) Part 21 file":
        "Blenderでモデリングしたポケットを、ISO 14649（STEP-NC）のPart 21ファイルとして書き出します",
    "Move the selected workingstep up or down in the workplan":
        "選択したワーキングステップをワークプラン内で上下に移動します",
    # A two-line docstring: Blender keeps its line break and indentation in the tooltip.
    "Cast rays from every face: colour it by the tool directions that reach it (blue radial,\n"
    "    green axial, purple both, grey neither)":
        "各面からレイを飛ばし、届く工具の方向で面を色分けします（青：径方向、緑：軸方向、紫：両方、灰：どちらも届かない）",
    "Classify the faces, then plan radial and axial roughing and finishing paths":
        "面を分類してから、径方向と軸方向の荒加工・仕上げ加工の経路を計算します",
    "Write the X-Z-C program (or its CL data) for the turn-mill centre":
        "複合加工機用のX-Z-Cプログラム（またはCLデータ）を書き出します",
    "Unfold the twisted quad by triangulation and lay the flat pattern beside it":
        "ねじれ四辺形を三角形分割で展開し、展開図を横に並べます",
    "Take the twisted quad's corners from the selected quad face of the active mesh":
        "アクティブなメッシュの選択した四角形面から、ねじれ四辺形の頂点を取得します",
    "Import a twisted quad from a CADKEY CDL intermediate file (four LINE records)":
        "CADKEY CDL中間ファイル（LINEレコード4本）からねじれ四辺形を読み込みます",
    "Write the turret-punch program (.nc) with the flat pattern as DXF and SVG beside it":
        "タレットパンチ用プログラム（.nc）と、展開図のDXF・SVGを同じ場所に書き出します",
    "Add a segmented pipe elbow and the flat pattern of every piece":
        "エビ管（分割したパイプエルボ）と、各ピースの展開図を追加します",
    "Write the elbow pieces' flat patterns as DXF and SVG, and a turret-punch program per piece":
        "エビ管の各ピースの展開図をDXFとSVGで、ピースごとのタレットパンチNCとともに書き出します",
}

# Panel and menu labels (bl_label), and the fixed texts of layout.label().
PANEL_TEXTS = {
    "Simulate & Check": "シミュレーションと検査",
    "No findings": "指摘なし",
    "Machine & Stock": "機械と素材",
    "Engrave": "彫刻",
    "Gouge Texture (Roughing)": "彫刻刀跡（荒加工）",
    "Band & Burr Finishing": "帯仕上げ・バリ取り",
    "Feeds & Heights": "送り速度と高さ",
    "Rotary Pockets": "回転テーブルポケット",
    "Bit, Feeds & Pitch": "ビット・送り・ピッチ",
    "STEP-NC Workplan": "STEP-NCワークプラン",
    "Write Pockets as ISO 14649": "ポケットをISO 14649で書き出し",
    "Turn-Mill": "複合加工",
    "Tool & Tolerance": "工具と公差",
    "Carve": "曲面加工",
    "Roughing": "荒加工",
    "Finishing, Feeds & Heights": "仕上げ・送り・高さ",
    "Sheet Metal": "板金",
    "Pipe Elbow": "エビ管",
    "Tool Library": "工具ライブラリ",
    "Quad corners (mm)": "四辺形の頂点 (mm)",
    "Pockets: objects marked as pockets": "ポケット：ポケット指定の輪郭",
    "The tool library has no ball or flat end mill (CAM > Tool Library)":
        "工具ライブラリにボールエンドミルもフラットエンドミルもありません（CAM > 工具ライブラリ）",
    # CAM tab (issue #21): parts of composed labels, finding kinds, a workingstep's operation word
    "Pockets": "ポケット",
    "Findings": "指摘",
    "Gouge": "削り込み",
    "Rapid in stock": "素材内の早送り",
    "Plunge": "突込み",
    "Spindle stopped": "主軸停止中",
    "Travel limit": "ストローク超過",
    "face rough": "正面荒",
    "face": "正面",
    "rough": "荒",
    "finish": "仕上げ",
    "drill": "穴あけ",
    "centre drill": "センタ穴",
    "ream": "リーマ",
}

# Property names and descriptions, enum items (operators/properties.py, preferences.py and the
# operators' own properties).
PROPERTY_TEXTS = {
    "Colour": "色分け",
    "Blocks Export": "書き出しを止める",
    "Write Despite Findings": "指摘があっても書き出す",
    "Setup Sheet": "段取りシート",
    "Also write <program>-setup-sheet.html beside the program, in the interface language: the machine, stock and "
    "work zero, tools, operations, feeds and the export gate's result":
        "プログラムの横に <program>-setup-sheet.html も書き出します（表示言語で）：機械、素材と原点、工具、工程、送り、書き出しゲートの結果",
    "Write the programs even if the punching simulation finds a part that stays in the sheet or a hit biting "
    "into the part":
        "パンチングのシミュレーションで、製品が板から外れない、または製品に食い込むヒットが見つかっても、プログラムを書き出します",
    "Export the program although the simulation found the faults listed above (only these: a different finding "
    "stops the export again)":
        "シミュレーションが上の不具合を見つけても、プログラムを書き出します（対象はこの指摘だけです。別の指摘があれば再び書き出しを止めます）",
    "Light wood at the top, dark at the deepest cut": "上面は明るく、最も深い切削ほど濃く",
    "Each operation's surface in its own colour": "各工程が仕上げた面をそれぞれの色で表示",
    # Simulation
    "Job": "ジョブ",
    "Engraving": "彫刻",
    "The gouge-texture name plate": "彫刻刀跡の表札",
    "The pockets on the rotating table": "回転テーブルのポケット",
    "The imported ISO 14649 workplan": "読み込んだISO 14649ワークプラン",
    "The turn-mill part's radial and axial operations": "複合加工部品の径方向・軸方向の加工工程",
    "Carving": "曲面加工",
    "Roughing and finishing of a 3-D surface (relief, domed plate, any mesh)":
        "3次元曲面（レリーフ、ドーム形の板、任意のメッシュ）の荒加工と仕上げ",
    "Kind": "種類",
    "Location": "位置",
    "Message": "メッセージ",
    "Move": "移動",
    "Cell Size": "セルサイズ",
    "Height-field grid spacing (mm)": "ハイトフィールドの格子間隔（mm）",
    "Engine": "エンジン",
    "Height Field": "ハイトマップ",
    "Fast Z-map of the exact tool envelope (3-axis and C-X-Z jobs)":
        "工具包絡面を正確に求める高速Zマップ（3軸とC-X-Zのジョブ）",
    "Exact Solid": "厳密ソリッド",
    "manifold3d booleans of the swept tools: exact, slower": "工具の掃引体のmanifold3dブーリアン：正確だが低速",
    # Posts and work offsets
    "Post": "ポストプロセッサ",
    "Controller the NC program is written for": "NCプログラムの出力先の制御装置",
    "Preferences Default": "プリファレンスの既定値",
    "The default post of the extension preferences": "エクステンションのプリファレンスで設定した既定のポストプロセッサ",
    "Work Offset": "ワーク座標系",
    "Work coordinate system selected at the program start": "プログラムの始めに選択するワーク座標系",
    **{f"G{n}": f"G{n}" for n in range(54, 60)},
    **{f"Work coordinate system G{n}": f"ワーク座標系 G{n}" for n in range(54, 60)},
    # Machine
    "Rapid Rate": "早送り速度",
    "Rapid traverse speed used for cycle-time estimates (mm/min)": "加工時間の見積もりに使う早送り速度 (mm/min)",
    "Output Folder": "出力フォルダー",
    "Folder for exported NC programs (empty: the preferences' folder)":
        "NCプログラムの書き出し先フォルダー（空欄：プリファレンスのフォルダー）",
    # Machine profile (Machine & Stock > Machine and its settings)
    "Machine": "機械",
    "The machine the programs are written for: travel, how high Z reaches, how the frames lift Z, the tool "
    "change (picking one fills the settings below)":
        "プログラムを書き出す対象の機械：ストローク、Zが届く高さ、Zの退避方法、工具交換（選ぶと下の設定に値が入ります）",
    "Post's Machine": "ポストの既定の機械",
    "The machine the chosen post's program assumes (its own preset)": "選んだポストのプログラムが前提とする機械（ポスト既定のプリセット）",
    "Hobby router (GRBL)": "ホビー用ルーター（GRBL）",
    "GRBL 1.1 hobby router, not homed, bits changed by hand at an M00 pause, Z zeroed on the top":
        "GRBL 1.1 のホビー用ルーター。原点復帰なし、M00 の一時停止で手で刃物を交換し、Zは上面でゼロ合わせ",
    "LinuxCNC, Manual Change": "LinuxCNC（手動工具交換）",
    "LinuxCNC router or mill, homed, M6 stops and asks for the tool (hal_manualtoolchange)":
        "LinuxCNC のルーターまたはフライス盤。原点復帰済み、M6 で停止して工具を求めます（hal_manualtoolchange）",
    "LinuxCNC, Tool Changer": "LinuxCNC（自動工具交換）",
    "LinuxCNC mill, homed, tool changer; M6 lifts Z (TOOL_CHANGE_QUILL_UP = 1)":
        "LinuxCNC フライス盤。原点復帰済み、自動工具交換装置付き。M6 でZが上がります（TOOL_CHANGE_QUILL_UP = 1）",
    "Machining centre (Fanuc 0i-MF)": "マシニングセンタ（FANUC 0i-MF）",
    "Fanuc 0i-MF vertical machining centre with a tool changer": "自動工具交換装置付きの FANUC 0i-MF 立形マシニングセンタ",
    "Wood Lathe C-X-Z (Fanuc)": "木工旋盤 C-X-Z（FANUC）",
    "Rotating face plate (C) with a ball bit on X and Z (seed 001)": "回転する面板（C）と、XとZで動くボールビット（シード001）",
    "Wood Lathe C-X-Z (LinuxCNC)": "木工旋盤 C-X-Z（LinuxCNC）",
    "Rotating face plate (C) with a ball bit on X and Z, homed LinuxCNC control (seed 001)":
        "回転する面板（C）と、XとZで動くボールビット。原点復帰済みの LinuxCNC 制御（シード001）",
    "Turn-mill (Fanuc 0i-T)": "複合加工機（FANUC 0i-T）",
    "Fanuc 0i-T turning centre with driven tools and a C axis (seed 003)":
        "回転工具とC軸を持つ FANUC 0i-T ターニングセンタ（シード003）",
    "Turret punch (Amada 04P)": "タレットパンチ（アマダ 04P）",
    "Amada turret punch press with the 04P control (seed 004)": "04P 制御のアマダ製タレットパンチプレス（シード004）",
    "Travel X": "ストローク X",
    "How far the X axis travels (mm)": "X軸の移動量 (mm)",
    "Travel Y": "ストローク Y",
    "How far the Y axis travels (0: no Y axis) (mm)": "Y軸の移動量（0：Y軸なし）(mm)",
    "Travel Z": "ストローク Z",
    "How far the Z axis travels (mm)": "Z軸の移動量 (mm)",
    "Z Reach": "Zの届く高さ",
    "How high above the work zero the tool can be lifted (mm)": "工具をワーク原点からどこまで上げられるか (mm)",
    "Clearance Height": "逃げ高さ",
    "Where the frames lift Z to on a machine without a machine-coordinate retract, above the work zero (mm)":
        "機械座標で退避できない機械で、開始・工具交換・終了時にZを上げる高さ（ワーク原点から）(mm)",
    "Retract": "Z退避",
    "How Z is lifted at the start, around tool changes and at the end": "開始時・工具交換の前後・終了時にZを上げる方法",
    "Reference Return": "原点復帰",
    "Fanuc G91 G28 Z0.: Z to the reference position (machine coordinates)": "FANUC G91 G28 Z0.：Zを原点（機械座標）へ",
    "Machine Z (G53)": "機械座標Z (G53)",
    "G53 G00 Z to Machine Top Z: needs a homed machine": "G53 G00 Z で「機械座標の上端Z」へ。原点復帰済みの機械が必要です",
    "G00 Z to the clearance height above the work zero (a machine not homed)":
        "G00 Z でワーク原点上の逃げ高さへ（原点復帰しない機械）",
    "Machine Top Z": "機械座標の上端Z",
    "Machine-coordinate Z of the top of travel (G53) (mm)": "Zストローク上端の機械座標値 (G53) (mm)",
    "Tool Change": "工具交換",
    "How a tool gets into the spindle": "工具を主軸に取り付ける方法",
    "Tool Changer": "自動工具交換",
    "M06 changes the tool": "M06 で工具を交換します",
    "Manual": "手動",
    "The operator changes the tool at a pause (M00, or an M6 that asks)": "一時停止中にオペレーターが工具を交換します（M00、または問い合わせる M6）",
    "M6 Lifts Z": "M6でZ上昇",
    "The changer's M6 lifts Z by itself (LinuxCNC TOOL_CHANGE_QUILL_UP)": "工具交換装置の M6 が自らZを上げます（LinuxCNC TOOL_CHANGE_QUILL_UP）",
    "Max Spindle": "最高主軸回転",
    "Fastest spindle speed (rpm)": "主軸の最高回転数 (rpm)",
    "Max Feed": "最大送り",
    "Fastest cutting feed (mm/min)": "最大の切削送り速度 (mm/min)",
    "Height where each operation starts and ends; 0: the machine's clearance height (tool changes and the program "
    "end lift Z as the machine profile says) (mm)":
        "各工程の開始・終了の高さ。0：機械の逃げ高さ（工具交換とプログラム終了時のZ退避は機械プロファイルに従います）(mm)",
    "Orient Spindle (M19)": "主軸オリエント (M19)",
    "Fanuc posts: M19 before each tool change, for a changer that needs the spindle keys aligned (a post "
    "without it refuses the export)":
        "Fanucポスト：工具交換の前ごとに M19 を書きます（主軸キーの位置合わせが要る交換装置向け。"
        "M19 のないポストでは書き出しを中止します）",
    "Arcs (G2/G3)": "円弧 (G2/G3)",
    "Milling posts write polylines that follow circles as G2/G3 arcs (within 0.01 mm, within the control's arc end "
    "check); off: every move as planned":
        "フライス用ポストは円に沿う折れ線を G2/G3 の円弧で書きます（0.01 mm 以内、制御装置の円弧終点チェックの範囲内）。"
        "オフ：すべての移動を計画どおりに書きます",
    # Stock
    "Plate": "板材",
    "The stock: a mesh whose top face is machined": "素材：上面を加工するメッシュ",
    "Work Zero": "ワーク原点",
    "Where the program's X0 Y0 Z0 is on the plate": "プログラムの X0 Y0 Z0 を板材のどこに置くか",
    "Top centre": "上面の中心",
    "Work zero at the centre of the plate's top face (as the paper programs it)":
        "ワーク原点を板材上面の中心に置きます（論文のプログラムと同じ）",
    "Top front-left corner": "上面の左手前の角",
    "Work zero at the front-left corner of the plate's top face": "ワーク原点を板材上面の左手前の角に置きます",
    # Engrave: letters and the gouge texture (roughing)
    "Letters": "文字",
    "Text, curve or mesh object with the lettering to leave standing":
        "彫り残す文字のテキスト・カーブ・メッシュオブジェクト",
    "More Letters": "追加の文字",
    "Optional: every Text, curve or mesh in this collection is lettering too":
        "任意：このコレクション内のテキスト・カーブ・メッシュもすべて文字として扱います",
    "Ball Diameter": "ボール径",
    "Roughing ball end mill diameter (mm)": "荒加工用ボールエンドミルの直径 (mm)",
    "Ball Tool No.": "ボールの工具番号",
    "Stepover": "ステップオーバー",
    "Distance between zigzag rows (mm)": "ジグザグの列の間隔 (mm)",
    "Raster Angle": "走査角度",
    "Direction of the zigzag rows from the X axis (degrees); the controller macro needs 0":
        "X軸から測ったジグザグの列の向き（度）。制御装置マクロでは 0 にしてください",
    "Letter Clearance": "文字との間隔",
    "How far the ball's centre keeps from the letters (mm)": "ボールの中心を文字からどれだけ離すか (mm)",
    "Base Depth": "基準深さ",
    "Depth the random gouges vary around (mm)": "ランダムな刀跡の深さの中心となる深さ (mm)",
    "Depth Step": "深さの刻み",
    "Gouge depths are multiples of this (mm)": "刀跡の深さはこの値の倍数になります (mm)",
    "Amplitude": "振幅",
    "Largest gouge depth above or below the base depth (mm)": "基準深さから上下に振れる刀跡の深さの最大値 (mm)",
    "Gouge Spacing": "刀跡の間隔",
    "A new random depth every this much travel along a row (mm)": "列に沿ってこの距離進むごとに新しいランダムな深さにします (mm)",
    "Gouge Motion": "刀跡の動き",
    "Ramp": "斜め直線",
    "Straight lines from one depth to the next (the paper)": "ある深さから次の深さへ直線で結びます（論文の方法）",
    "Scoop": "すくい彫り",
    "Dive to the depth, then push up, like a hand gouge": "手彫りの丸ノミのように、深さまで突っ込んでからすくい上げます",
    "Spacing Jitter": "間隔のばらつき",
    "Vary each gouge length by up to this fraction (baked only)": "各刀跡の長さを最大でこの割合だけ変えます（ベイク時のみ）",
    "Seed": "シード",
    "Random seed of the baked texture: same seed, same program": "ベイクするテクスチャの乱数シード：同じシードなら同じプログラム",
    "Plate Surface": "板材の曲面",
    "Optional: a mesh whose top is the plate's curved top (a dome, a cylinder, a sculpted board), spanning the "
    "whole plate outline; the toolpaths follow it.  Empty: the flat top of the plate":
        "任意：上面が板材の曲がった上面になるメッシュ（ドーム、円筒、スカルプトした板など）。板材の輪郭全体を覆うこと。"
        "ツールパスはこの面に沿います。空欄なら板材の平らな上面です",
    # Engrave: band finishing and burr contour
    "Flat Diameter": "フラット径",
    "Band finishing flat end mill diameter (mm)": "帯仕上げ用フラットエンドミルの直径 (mm)",
    "Flat Tool No.": "フラットの工具番号",
    "Band Width": "帯の幅",
    "Width of the flat band cut around every letter (mm)": "各文字の周りに平らに削る帯の幅 (mm)",
    "Band Depth": "帯の深さ",
    "Depth of the band around the letters (mm)": "文字の周りの帯の深さ (mm)",
    "Band Stepover": "帯のステップ",
    "Distance between the band's contour passes (mm)": "帯の輪郭加工パスの間隔 (mm)",
    "Band Step Down": "帯の切込み",
    "Deepest cut of one level of the band: at most the flat end mill's diameter (mm)":
        "帯の1段の最大切込み：フラットエンドミルの直径以下 (mm)",
    "Band Ramp Angle": "帯のランプ角度",
    "Each level of the band is entered on a ramp along the ring at this angle (degrees); the flat end mill never "
    "plunges straight down":
        "帯の各段へはリングに沿ってこの角度の斜め送りで入ります（度）。フラットエンドミルを真下に突っ込みません",
    # Engrave: feeds and heights
    "Ball Spindle": "ボールの主軸回転数",
    "Flat Spindle": "フラット回転数",
    "Spindle speed (rpm)": "主軸回転数 (rpm)",
    "Ball Feed": "ボールの送り速度",
    "Flat Feed": "フラットの送り速度",
    "Cutting feed (mm/min)": "切削送り速度 (mm/min)",
    "Plunge Feed": "突込み送り速度",
    "Plunge feed (mm/min)": "突込み送り速度 (mm/min)",
    "Clearance Plane": "クリアランス高さ",
    "Height of rapid moves between cuts (mm)": "切削の合間に早送りで移動する高さ (mm)",
    "Safe Z": "安全高さ Z",
    "Height for tool changes and the program end (mm)": "工具交換とプログラム終了のときの高さ (mm)",
    "Show Rapids": "早送りを表示",
    # Sheet metal: twisted quad
    "Corners": "頂点",
    "P1..P4 of the twisted quad, x y z each (mm)": "ねじれ四辺形の P1～P4、それぞれ x y z (mm)",
    "Divisions N": "分割数 N",
    "Every edge of the quad is divided into N equal parts": "四辺形の各辺を N 等分します",
    "Strips": "帯の向き",
    "Horizontal (YR)": "横 (YR)",
    "Strips joining edges L1 and L3": "辺 L1 と L3 を結ぶ帯",
    "Vertical (TR)": "縦 (TR)",
    "Strips joining edges L2 and L4": "辺 L2 と L4 を結ぶ帯",
    "Tool Diameter": "工具径",
    "Punch diameter: the cut contour is offset by its radius (mm)":
        "パンチ径：切断輪郭はその半径だけオフセットされます（工具径補正） (mm)",
    "Sheet Thickness": "板厚",
    "Sheet thickness; above 3.2 mm the punching line G79 is used (mm)":
        "板厚。3.2 mm を超えるとパンチングライン G79 を使います (mm)",
    "Nibbling Pitch": "ニブリングピッチ",
    "Distance between punch hits (Q word) (mm)": "パンチの打ち抜き間隔（Qワード） (mm)",
    "Station": "ステーション",
    "Turret station (T word)": "タレットのステーション（Tワード）",
    # Sheet metal: the sheet, its clamps and the micro-joints (issue 26)
    "Sheet, Clamps & Joints": "板材・クランプ・ミクロジョイント",
    "G92 Origin": "G92 原点",
    "The program origin the control is told (G92 X Y, mm)": "NC装置に指令するプログラム原点（G92 X Y、mm）",
    "Sheet": "板材",
    "The sheet the part is placed on, X along the clamped edge (mm)": "部品を配置する板材。X はクランプ側の辺に沿う (mm)",
    "Clamps": "クランプ",
    "Clamp centres along the sheet's clamped edge, X from the sheet's corner (mm, separated by commas)":
        "板材のクランプ側の辺に沿ったクランプ中心の X 位置（板材の角から、mm、カンマ区切り）",
    "Clamp Width": "クランプ幅",
    "Width of each clamp's dead zone along X (mm)": "各クランプの加工禁止域の X 方向の幅 (mm)",
    "Clamp Depth": "クランプ奥行き",
    "Depth of each clamp's dead zone into the sheet (mm)": "各クランプの加工禁止域の板材内への奥行き (mm)",
    "Micro-Joints": "ミクロジョイント",
    "Webs left uncut on the part's outline so it stays in the sheet (0: the part falls free at the last hits)":
        "部品が板材に残るよう輪郭に切り残す継ぎ（0：最後の打ち抜きで部品が落ちます）",
    "Joint Width": "ジョイント幅",
    "Width of the web each micro-joint leaves (mm)": "各ミクロジョイントが残す継ぎの幅 (mm)",
    # Sheet metal: pipe elbow
    "Pipe Diameter": "管径",
    "Neutral diameter of the pipe (mm)": "管の中立径（板厚中心の径） (mm)",
    "Bend Radius": "曲げ半径",
    "Radius of the elbow's centre line (mm)": "エルボ中心線の半径 (mm)",
    "Bend Angle": "曲げ角度",
    "Angle the elbow turns the pipe through (degrees)": "エルボで管が曲がる角度（度）",
    "Pieces": "ピース数",
    "Pieces in all, the two half pieces at the ends included": "両端の半ピース2つを含む、全体のピース数",
    # Rotary pockets (per object)
    "Rotary Pocket": "回転テーブルポケット",
    "This closed curve or mesh outlines a pocket on the rotating table":
        "この閉じたカーブまたはメッシュは、回転テーブル上のポケットの輪郭です",
    "Depth": "深さ",
    "Depth of the pocket below the block's top (mm)": "ブロック材の上面からのポケットの深さ (mm)",
    "Wall Angle": "壁面角度",
    "Wall slope from vertical (degrees); 0 = vertical wall": "垂直からの壁面の傾き（度）。0 = 垂直な壁",
    "Bottom": "底面",
    "Flat": "平底",
    "A flat floor, cleared by one spiral": "平らな底面を、1本のスパイラルで削ります",
    "Spherical Bowl": "球面の椀形",
    "A concave spherical bowl, cut by a spiral on the sphere": "くぼんだ球面の椀形を、球面上のスパイラルで削ります",
    "Sphere Radius": "球の半径",
    "Radius of the spherical bowl (mm)": "球面の椀形の半径 (mm)",
    # Rotary: bit, feeds and pitch
    "Bit Diameter": "ビット径",
    "Ball-nose (pencil) bit diameter (mm)": "ボールエンド（ペンシル）ビットの直径 (mm)",
    "Bit Tool No.": "ビットの工具番号",
    "Flute Length": "刃長",
    "Cutting length of the bit: pockets may not be deeper (mm)": "ビットの刃長：ポケットはこれより深くできません (mm)",
    "Spindle": "主軸回転数",
    "Router speed (rpm)": "ルーターの回転数 (rpm)",
    "Cutting Speed": "切削送り速度",
    "Feed along the path on the wood (mm/min); written as inverse-time G93 feeds":
        "木材上の経路に沿った送り速度 (mm/min)。逆時間送り G93 で書き出します",
    "Plunge Speed": "突込み速度",
    "mm/min": "mm/min",
    "Point Spacing": "点の間隔",
    "Distance between path points (the paper's alpha) (mm)": "経路上の点の間隔（論文の α） (mm)",
    "Helix Pitch": "らせんピッチ",
    "Pitch of the floor and bowl spirals (the paper's P) (mm)": "底面と椀形のスパイラルのピッチ（論文の P） (mm)",
    "Step-Down": "切込み深さ",
    "Deepest roughing layer (mm)": "荒加工の1層あたりの最大切込み深さ (mm)",
    "Allowance": "仕上げ代",
    "Stock roughing leaves for finishing (mm)": "荒加工で仕上げ用に残す取り代 (mm)",
    "Wall Stepover": "壁面ステップ",
    "Wall finishing pitch along the wall (mm)": "壁面に沿った壁面仕上げのピッチ (mm)",
    "Table Speed Limit": "テーブル上限回転",
    "Fastest the face plate turns (rpm), for feeds and times": "面板の最高回転数 (rpm)。送り速度と加工時間の計算に使います",
    # STEP-NC (ISO 14649) workplan
    "Instance": "インスタンス番号",
    "Instance number (#id) in the Part 21 file": "Part 21ファイル内のインスタンス番号（#id）",
    "Name": "名前",
    "Feature": "フィーチャー",
    "Operation": "加工工程",
    "Cut": "加工する",
    "Include this workingstep in the NC program": "このワーキングステップをNCプログラムに含めます",
    "ISO 14649 File": "ISO 14649ファイル",
    "The imported Part 21 file; export converts it again": "読み込んだPart 21ファイル。書き出しのたびに変換し直します",
    "Active Workingstep": "アクティブなワーキングステップ",
    "End Mill Diameter": "エンドミル径",
    "Flat end mill for pockets written as ISO 14649 (mm)": "ISO 14649で書き出すポケット用のフラットエンドミル径 (mm)",
    "End Mill Tool No.": "エンドミル番号",
    "Cutting length of the end mill (mm)": "エンドミルの刃長 (mm)",
    "Feed": "送り速度",
    "Up": "上へ",
    "Down": "下へ",
    # Turn-mill
    "Part": "部品",
    "The part: a mesh around the Z axis (the C axis)": "部品：Z軸（C軸）まわりのメッシュ",
    "Selected Faces Only": "選択面のみ",
    "Machine only the faces selected in Edit Mode (all faces still block the rays)":
        "編集モードで選択した面だけを加工します（レイの遮りはすべての面で判定します）",
    "Stock Radius": "素材半径",
    "Radius of the round bar stock (85 mm chemical wood: 42.5) (mm)":
        "丸棒素材の半径（直径85 mmのケミカルウッドなら 42.5） (mm)",
    "Stock Z Min": "素材 Z 最小",
    "Chuck side of the stock (mm)": "素材のチャック側の端 (mm)",
    "Stock Z Max": "素材 Z 最大",
    "End face of the stock (mm)": "素材の端面 (mm)",
    "Ball end mill on both turret stations (mm)": "両方のタレットステーションのボールエンドミルの直径 (mm)",
    "Chordal Tolerance": "弦誤差の許容値",
    "Point spacing and scallops follow this tolerance (mm)": "点の間隔とカスプ高さをこの許容値に合わせます (mm)",
    "Ray Spacing": "レイの間隔",
    "Distance between ray samples on each face (mm)": "各面上のレイのサンプル点の間隔 (mm)",
    "Driven tool speed (rpm)": "回転工具の回転数 (rpm)",
    "Ray Engine": "レイ判定エンジン",
    "Blender BVH": "Blender BVH",
    "Blender's BVHTree": "BlenderのBVHTree",
    "trimesh": "trimesh",
    "trimesh (Embree when bundled), as in batch runs": "trimesh（同梱されていればEmbree）。バッチ実行と同じです",
    # Carve (3-D surfaces)
    "Clearance": "クリアランス",
    "Step Down": "切込み深さ",
    "Design": "設計形状",
    "The surface to carve: a mesh in work coordinates, its top at the stock top":
        "加工する曲面：ワーク座標のメッシュ（上端を素材の上面に合わせる）",
    "Stock Above": "上面の余肉",
    "How far the stock's top stands above the design's highest point (mm)":
        "素材の上面が設計形状の最も高い点からどれだけ上にあるか (mm)",
    "Rough in Z levels with the flat end mill before finishing": "仕上げの前にフラットエンドミルで Z 等高線荒加工をします",
    "Roughing Diameter": "荒加工の工具径",
    "Flat end mill for roughing (mm)": "荒加工用フラットエンドミルの直径 (mm)",
    "Roughing Tool No.": "荒加工の工具番号",
    "Tool number of the roughing end mill": "荒加工エンドミルの工具番号",
    "Stock roughing leaves on the design (mm)": "荒加工が設計形状の上に残す取り代 (mm)",
    "Depth between roughing levels (mm)": "荒加工の段と段の深さ (mm)",
    "Roughing Stepover": "荒ピックフィード",
    "Distance between roughing passes (mm)": "荒加工のパスの間隔 (mm)",
    "Ball end mill for finishing (mm)": "仕上げ用ボールエンドミルの直径 (mm)",
    "Ball Tool Number": "ボールの工具番号",
    "Tool number of the finishing ball end mill": "仕上げボールエンドミルの工具番号",
    "Scallop Height": "カスプ高さ",
    "Height of the ridges the ball may leave between passes; the stepover follows from it (mm)":
        "パスの間にボールが残してよい山の高さ。ピックフィードはこれから決まります (mm)",
    "Direction of the finishing passes, degrees from +X": "仕上げパスの向き（+X からの角度、度）",
    "Max Slope": "最大傾斜",
    "Faces steeper than this across the raster do not shrink its stepover: the Steep Cleanup and the Wall Pass "
    "finish them (degrees)":
        "走査に直交する方向でこれより急な面は走査のピックフィードを狭めません。急斜面の追加仕上げと壁の等高線仕上げが"
        "仕上げます（度）",
    "Point Spacing": "点の間隔",
    "Distance between points along a pass (refined where the surface bends) (mm)":
        "パスに沿った点の間隔（曲面が曲がるところでは細かくします） (mm)",
    "Roughing Spindle": "荒加工の主軸回転数",
    "Spindle speed for roughing (rpm)": "荒加工の主軸回転数 (rpm)",
    "Finishing Spindle": "仕上げの主軸回転数",
    "Spindle speed for finishing (rpm)": "仕上げの主軸回転数 (rpm)",
    "Roughing Feed": "荒加工の送り速度",
    "Roughing feed (mm/min)": "荒加工の送り速度 (mm/min)",
    "Finishing Feed": "仕上げの送り速度",
    "Finishing feed (mm/min)": "仕上げの送り速度 (mm/min)",
    "Feed into the work (mm/min)": "ワークへの突込み送り速度 (mm/min)",
    "Height above the stock top for moves between cuts (mm)": "切削と切削の間を移動する、素材上面からの高さ (mm)",
    "Height above the stock top at the start and the end (mm)": "開始時と終了時の素材上面からの高さ (mm)",
    "Show the rapid moves in the preview": "プレビューに早送りを表示します",
    "Sample": "サンプル",
    "Wave Relief": "波のレリーフ",
    "A 120 x 80 mm plate with a wave on top": "上面が波形の 120 x 80 mm の板",
    "Domed Plate": "ドーム形の銘板",
    "A 160 x 60 mm domed name plate with a raised ring": "縁に盛り上がった輪のある 160 x 60 mm のドーム形銘板",
    "Steep Ridge": "急斜面の尾根",
    "A 100 x 60 mm plate with a ridge along X, its flanks sloping 55 degrees":
        "X 方向に尾根が走り、その斜面が 55 度で傾く 100 x 60 mm の板",
    "Walled Block": "壁のあるブロック",
    "An 80 x 60 mm plate with a raised block and a pocket, their walls one 0.5 mm grid cell wide (a height-image "
    "relief)": "盛り上がったブロックとポケットのある 80 x 60 mm の板。壁は 0.5 mm の格子 1 目の幅（高さ画像のレリーフ）",
    "Vertical Block": "垂直壁のブロック",
    "The same block and pocket with vertical walls": "同じブロックとポケットで、壁が垂直なもの",
    "Wall Pass": "壁の等高線仕上げ",
    "Finish the walls no raster finishes (vertical, or steeper than Max Slope across both rasters) by waterlines, Z "
    "steps chosen from the scallop height":
        "走査では仕上がらない壁（垂直、または両方の走査に直交する方向で最大傾斜より急な壁）を等高線で仕上げます。"
        "Z のステップはカスプ高さから決めます",
    "Steep Cleanup": "急斜面の追加仕上げ",
    "Cut the faces steeper across the raster than Max Slope again, with a raster across the first, so the "
    "scallop there stays within the height asked":
        "走査に直交する方向で最大傾斜より急な面を、最初の走査に直交する走査でもう一度削り、そこのカスプ高さを"
        "指定の高さ以内に収めます",
    # Preferences: tool library
    "Number": "工具番号",
    "Tool (pocket) number, T word": "工具（ポット）番号、Tワード",
    "Type": "種類",
    "Ball End Mill": "ボールエンドミル",
    "Ball-nose end mill": "先端が球状のボールエンドミル",
    "Flat End Mill": "フラットエンドミル",
    "Square end mill": "スクエアエンドミル（先端が平ら）",
    "Bull Nose": "ラジアスエンドミル",
    "End mill with a corner radius": "コーナーRの付いたエンドミル",
    "Drill": "ドリル",
    "Twist drill": "ツイストドリル",
    "V-Bit": "Vビット",
    "Engraving V-bit": "彫刻用Vビット",
    "Diameter": "直径",
    "Cutting diameter (mm)": "刃径 (mm)",
    "Corner Radius": "コーナーR",
    "Bull nose radius (mm)": "ラジアスエンドミルのコーナー半径 (mm)",
    "Cutting length (mm)": "切れ刃の長さ (mm)",
    "Default Post": "既定のポストプロセッサ",
    "Controller a new job is exported for": "新しいジョブの書き出し先の制御装置",
    "Default Work Offset": "既定のワーク座標系",
    "Where NC programs go unless the scene says otherwise (// = beside the .blend file)":
        "シーンで指定しない場合のNCプログラムの保存先（// = .blendファイルと同じ場所）",
    # Operator properties
    "For": "用途",
    "Roughing Ball": "荒加工用ボール",
    "Finishing Flat": "仕上げ用フラット",
    "Library Index": "ライブラリ内の番号",
    "Pocket": "ポケット",
    # CAM tab (issue #21): the job picker, the workingstep list's columns
    "The job the CAM tab shows: its panels, and Machine & Stock": "CAMタブに表示するジョブ（そのパネルと機械・素材）",
    "Twisted quads and pipe elbows: flat patterns, turret-punch NC, DXF, SVG":
        "ねじれ四辺形とエビ管：展開図、タレットパンチNC、DXF、SVG",
    "Feature Name": "フィーチャ名",
    "The feature's name in the file": "ファイル内のフィーチャの名前",
    "Step": "工程",
    "The operation in a word (rough, finish, drill ...)": "加工工程をひとことで（荒、仕上げ、穴あけ…）",
    "Tool": "工具",
    "Tool number and diameter": "工具番号と工具径",
}

# Fixed messages: poll messages, reports and the errors the operators show (run_reported).
MESSAGES = {
    "the design mesh was inside out (its normals pointed inward); its faces were flipped":
        "デザインメッシュが裏返しでした（法線が内向き）。面を反転しました",
    # turret punch on the sheet (issue 26)
    "a line has a non-finite coordinate (NaN or infinity)": "線に有限でない座標（NaN または無限大）があります",
    "the contour has fewer than 3 corners once collinear points are merged":
        "一直線上の点をまとめると、輪郭の角が3つ未満になります",
    "a contour must be finite (x, y) points": "輪郭は有限の (x, y) 点で与えてください",
    "placing a part needs its contour as finite (x, y) points": "部品の配置には有限の (x, y) 点の輪郭が必要です",
    "joints: every joint is two finite hit centres": "ジョイント：各ジョイントは有限な2つの打ち抜き中心で与えてください",
    "joints need the pattern: the part held by them is the piece holding the pattern":
        "ジョイントには展開図が必要です（ジョイントで保持される部品は展開図を含む部分です）",
    "This job is already running: wait for it or press Esc to cancel it": "この処理は実行中です。終わるまで待つか、Escで中止してください",
    "Cancelled: the scene is as it was": "中止しました。シーンは元のままです",
    "Esc to cancel": "Escで中止",
    # operators/*.py
    "Pick the plate (stock) object first": "先に板材（素材）のオブジェクトを選んでください",
    "Pick the letters (Text, curve or mesh) first": "先に文字（テキスト・カーブ・メッシュ）を選んでください",
    "Pick the block (stock) object first": "先にブロック材（素材）のオブジェクトを選んでください",
    "Select closed curves or meshes that outline the pockets": "ポケットの輪郭になる閉じたカーブかメッシュを選択してください",
    "Make a mesh with a quad face the active object": "四角形の面を持つメッシュをアクティブオブジェクトにしてください",
    "Select a tool in the library first": "先に工具ライブラリで工具を選択してください",
    "Import an ISO 14649 file first": "先にISO 14649ファイルを読み込んでください",
    "Pick the part (a mesh) in the Turn-Mill panel": "複合加工パネルで部品（メッシュ）を選んでください",
    "pick the part (a mesh around the Z axis) in the Turn-Mill panel":
        "複合加工パネルで部品（Z軸まわりのメッシュ）を選んでください",
    "Pick the design (a mesh) in the Carve panel": "曲面加工パネルで設計形状（メッシュ）を選んでください",
    "pick the design (a mesh) in the Carve panel": "曲面加工パネルで設計形状（メッシュ）を選んでください",
    "Corners taken from the selected face": "選択した面から頂点を取得しました",
    "Kezuri preferences are not available": "Kezuriのプリファレンスを利用できません",
    "no file given: the file path is empty": "ファイルが指定されていません：ファイルパスが空です",
    "no plate: pick the stock object (a mesh) in the CAM panel":
        "板材がありません：CAMパネルで素材のオブジェクト（メッシュ）を選んでください",
    "no letters: pick a Text, curve or mesh object as Letters in the Engrave panel":
        "文字がありません：彫刻パネルの「文字」にテキスト・カーブ・メッシュのオブジェクトを選んでください",
    "no pockets: mark outline objects as pockets in the Rotary Pockets panel":
        "ポケットがありません：回転テーブルポケットパネルで輪郭オブジェクトをポケットに指定してください",
    "select a mesh object with a quad face (four straight edges)":
        "四角形の面（直線の辺4本）を持つメッシュオブジェクトを選択してください",
    "no ISO 14649 file: use File > Import > ISO 14649 first":
        "ISO 14649ファイルがありません：先に ファイル > インポート > ISO 14649 で読み込んでください",
    "every workingstep is switched off: nothing to export":
        "ワーキングステップがすべてオフです：書き出すものがありません",
    "no pockets: mark closed outline objects as pockets (with a depth)":
        "ポケットがありません：閉じた輪郭オブジェクトを（深さを付けて）ポケットに指定してください",
    # toolpath/operations/engrave/engrave.py
    "texture quantum and gouge spacing must be > 0, amplitude >= 0":
        "テクスチャの深さの刻みと刀跡の間隔は 0 より大きく、振幅は 0 以上にしてください",
    "scoop dive fraction must be between 0 and 1": "すくい彫りの突込みの割合は 0～1 にしてください",
    "spacing jitter must be between 0 and 0.5": "間隔のばらつきは 0～0.5 にしてください",
    "the shallowest gouge (base depth + amplitude) would lie above the plate top":
        "最も浅い刀跡（基準深さ＋振幅）が板材の上面より上になってしまいます",
    "gouge digits must be 0..9": "刀跡の数字は 0～9 にしてください",
    "band and burr depths must be below the plate top (negative Z)":
        "帯とバリ取りの深さは板材の上面より下（Z がマイナス）にしてください",
    "heights must satisfy 0 < approach gap < clearance plane <= safe Z":
        "高さは 0 < アプローチの隙間 < クリアランス高さ <= 安全高さ Z を満たす必要があります",
    "no letters: select a Text, curve or mesh object to engrave around":
        "文字がありません：周りを彫るテキスト・カーブ・メッシュのオブジェクトを選択してください",
    "nothing to cut: the letters leave no room on the plate for the tools":
        "削るところがありません：文字で板材が埋まり、工具が入る余地がありません",
    # toolpath/operations/rotary/rotary.py
    "a cutting move could not be linearised for the rotary table (path through the axis?)":
        "切削の移動を回転テーブル用に直線化できませんでした（経路が回転軸を通っていませんか？）",
    "no pockets to cut": "削るポケットがありません",
    # toolpath/operations/sheetmetal/unfold.py
    "corner coordinates must be finite (no NaN or infinity)": "頂点の座標は有限の値にしてください（NaN や無限大は使えません）",
    "cannot lay a triangle on a zero-length edge (two strip points coincide)":
        "長さ 0 の辺には三角形を置けません（帯の2点が重なっています）",
    "edge lengths violate the triangle inequality (corrupt strip geometry)":
        "辺の長さが三角不等式を満たしません（帯の形状が壊れています）",
    "the flat pattern overlaps itself; split the strip into shorter pieces":
        "展開図が自分自身と重なります。帯をもっと短いピースに分けてください",
    "round centre offset must be finite": "丸側の中心のずれは有限の値にしてください",
    "outline has a non-finite coordinate (NaN or infinity)": "輪郭に有限でない座標（NaN または無限大）があります",
    "outline has fewer than 3 distinct points": "輪郭の異なる点が3つ未満です",
    "outline encloses no area": "輪郭が面積を囲んでいません",
    # toolpath/simulate/
    "nothing to simulate: the program has no moves": "シミュレーションするものがありません：プログラムに移動がありません",
    "design surface has NaN heights": "設計面の高さに NaN があります",
    "simulation cancelled": "シミュレーションを中止しました",
    "simulate needs a Program, an Operation or a list of Operations":
        "シミュレーションには Program、Operation、または Operation のリストが必要です",
    "the stock's top surface does not cover the plate": "素材の上面の曲面が板材を覆っていません",
    'a plate with a curved top is simulated on the height field only (engine "heightfield")':
        '上面が曲面の板材はハイトフィールドでのみシミュレーションできます（エンジン "heightfield"）',
    # toolpath/engines/dropcutter.py, toolpath/operations/carve/carve.py
    "a vertex has a non-finite coordinate": "頂点に有限でない座標があります",
    "a query point has a non-finite coordinate": "問い合わせ点に有限でない座標があります",
    "a path needs at least two points": "経路には少なくとも2点が必要です",
    "the design mesh has no triangles": "設計形状のメッシュに三角形がありません",
    "the design mesh has a non-finite vertex": "設計形状のメッシュに有限でない頂点があります",
    "the design does not lie over the simulated stock": "設計形状がシミュレーションした素材の上にありません",
    "design must be a function z(x, y), a mesh with vertices and faces, or a number":
        "設計形状は関数 z(x, y)、頂点と面を持つメッシュ、または数値で指定してください",
    "radial turn-mill operations cut a bar: give a cylinder stock about the C axis":
        "ラジアル方向のターンミル工程は丸棒を削ります：C軸まわりの円柱素材を指定してください",
    # toolpath/simulate/ncread.py
    "the NC file has no moves": "NCファイルに移動がありません",
    # toolpath/operations/sheetmetal/punch.py
    "a punch program must be text": "パンチプログラムはテキストにしてください",
    "the program has no end (G50 or M30)": "プログラムに終わり（G50 または M30）がありません",
    "the program punches nothing: no G69 or G79 line": "プログラムは何も打ち抜きません：G69 も G79 の行もありません",
    "the scallop needs a diameter > 0 and a pitch >= 0": "スカラップには 0 より大きい直径と 0 以上のピッチが必要です",
    "pattern: an outline must be a list of (x, y) points": "展開図：輪郭は (x, y) 点のリストにしてください",
    "simulate_punching needs the NC text or a PunchProgram":
        "simulate_punching には NC テキストまたは PunchProgram が必要です",
    "margin must be a number > 0": "余白は 0 より大きい数にしてください",
    "the program's lines are tool-centre paths (P0): give the punch diameter":
        "プログラムの線は工具中心の経路（P0）です：パンチの直径を指定してください",
    "the pattern does not overlap what is left of the sheet: are the pattern and the program in the same coordinates?":
        "展開図が残った板と重なりません：展開図とプログラムは同じ座標系ですか？",
    # toolpath/operations/stepnc/part21.py
    "None is not a Part 21 value; use UNSET for '$'": "None は Part 21 の値ではありません。'$' には UNSET を使ってください",
    "a complex instance needs at least one part": "複合インスタンスには少なくとも1つの部分が必要です",
    # toolpath/operations/turnmill/turnmill.py
    "the mesh is empty: it needs vertices and triangles": "メッシュが空です：頂点と三角形が必要です",
    "the mesh has NaN or infinite vertex coordinates": "メッシュの頂点座標に NaN または無限大があります",
    "a face uses the same vertex twice": "同じ頂点を2回使っている面があります",
    "the faces are wound inconsistently (some normals are flipped): recalculate normals":
        "面の向きがそろっていません（一部の法線が反転しています）：法線を再計算してください",
    "nothing to machine: no radially or axially reachable face lies inside the stock":
        "加工するところがありません：素材の内側に、半径方向からも軸方向からも工具が届く面がありません",
    "the radial and axial tools need different turret stations":
        "半径方向の工具と軸方向の工具には別々のタレットステーションが必要です",
    "vertices and faces must be numeric arrays": "頂点と面は数値の配列にしてください",
    "the face normals point inward: flip them so they point out of the part":
        "面の法線が内側を向いています：部品の外側を向くように反転してください",
    # toolpath/operations/stepnc/workplan.py: notes the STEP-NC operators report as warnings
    "the workplan has no workingstep": "ワークプランにワーキングステップがありません",
    "the reduced spindle speeds of DRILLING_TYPE_STRATEGY are not written (one spindle speed per operation)":
        "DRILLING_TYPE_STRATEGY の減速した主軸回転数は書き出しません（主軸回転数は工程ごとに1つです）",
    "the spindle is not stopped at the bottom (not written); the reamer is fed out":
        "穴底での主軸停止は書き出しません。リーマは回転したまま送りで抜きます",
    # post/*.py
    "a closed contour needs at least 3 distinct points": "閉じた輪郭には異なる点が3つ以上必要です",
    "G92 origin must be finite": "G92 の原点は有限の値にしてください",
    "the controller-macro post needs an operation with a gouge texture; use the baked Fanuc post for this program":
        "制御装置マクロのポストプロセッサには彫刻刀跡テクスチャ付きの工程が必要です："
        "このプログラムにはベイク版のFANUCポストプロセッサを使ってください",
    "all textured operations must share one texture: O7023 is one program":
        "テクスチャ付きの工程はすべて同じテクスチャにしてください：O7023 は1本のプログラムです",
    "bend lines: non-finite coordinate": "曲げ線：有限でない座標があります",
    "nothing to export": "書き出すものがありません",
    "the program has no operations": "プログラムに加工工程がありません",
    'the NC program must be text': 'NCプログラムはテキストにしてください',
    # toolpath/pictures/picture.py, toolpath/pictures/picture_jobs.py
    "nothing to draw: no finite point to frame": "描くものがありません：枠に収める有限の点がありません",
    "no pattern to draw": "描く展開図がありません",
    # jobs (issue 28)
    "--jobs is for the rows of --each": "--jobs は --each の行のためのものです",
    "--font is for --text": "--font は --text のためのものです",
    "give --text or --svg/--dxf, not both": "--text か --svg/--dxf のどちらか一方を指定してください",
    "the job has no operation switched on": "ジョブに有効な加工がありません",
    "a design mesh can only be the job's one design layer for now":
        "設計メッシュは、現在ジョブの唯一の設計レイヤーとしてのみ使えます",
}


# A value: a quoted name (``{name!r}``) whole where one stands there, so a name holding the text
# that follows it in the template ("'roughing (gouge texture)' (T2 ...") is not cut at it; else
# the shortest text that lets the rest match.
_VALUE = r"('(?:[^'\\\n]|\\.)*'(?=%s)|.*?)"


def _template_pattern(template: str):
    """An anchored regex for an English template: literal text escaped, each ``{}`` a group."""
    parts = [re.escape(part.replace("{{", "{").replace("}}", "}")) for part in template.split("{}")]
    pattern = parts[0]
    for following in parts[1:]:
        pattern += (_VALUE % following if following else "(.*?)") + following
    return re.compile(pattern + r"\Z", re.DOTALL)


def _compiled_templates() -> list:
    """(regex, Japanese) for every template, the most literal text first: the most specific wins."""
    ordered = sorted(MESSAGE_TEMPLATES.items(), key=lambda item: -len(item[0].replace("{}", "")))
    return [(_template_pattern(english), japanese, INTERFACE_NAMES.get(english, ()), NESTED.get(english, ()))
            for english, japanese in ordered]


def iface(text: str) -> str:
    """``text`` in the interface language, for a label put together from parts (Blender
    translates a label's whole text only)."""
    return bpy.app.translations.pgettext_iface(text)


def reports_in_japanese() -> bool:
    """Whether Blender translates reports now (interface language Japanese, reports on)."""
    probe = next(iter(MESSAGES))
    return bpy.app.translations.pgettext_rpt(probe) != probe


def translate_message(text: str) -> str:
    """A report or error message in the interface language: a fixed message, or an f-string
    message filled into its Japanese template; English when nothing matches."""
    fixed = bpy.app.translations.pgettext_rpt(text)
    if fixed != text or not reports_in_japanese():
        return fixed
    return japanese_message(text) or text


def japanese_message(text: str) -> str | None:
    """The Japanese of a message built from an f-string (its values filled into the template),
    or None when no template matches."""
    for pattern, japanese, names, nested in _COMPILED:
        match = pattern.match(text)
        if match:
            values = list(match.groups())
            for index in nested:         # a message with a template of its own, or a fixed one
                values[index] = japanese_message(values[index]) or _interface_name(values[index])
            for index in names:         # a panel's name or a property's label, wherever it appears
                english = _NAMED.match(values[index]).group(1)
                if not english:
                    continue
                shown = _interface_name(english)
                values = [value.replace(english, shown) for value in values]
            return japanese.format(*values)
    name, colon, rest = text.partition(": ")       # a message under the name of the file it is about
    if colon:                                      # (textfile.named: "--cdl q.cdl: CDL line 7: ...")
        inner = japanese_message(rest) or TRANSLATIONS[LOCALE].get((DEFAULT, rest))
        if inner:
            return f"{name}：{inner}"
    return None


_NAMED = re.compile(r"(.*?)(?: '.*'| \[\d+\])?$")   # "Tool Library 'T1'" / "Corners [3]" -> the name


def _interface_name(english: str) -> str:
    """A panel name, property label or fixed message as the Japanese interface shows it (else unchanged)."""
    return TRANSLATIONS[LOCALE].get((DEFAULT, english), english)


# Templates whose values include interface names (panel, property label): those values'
# positions, so the message uses the words the user sees on the panel.
INTERFACE_NAMES = {"{}: {} = {} is outside the allowed range {}": (0, 1),
                   "{}: {} = {} mm must be less than {} = {} mm: hits a diameter or more apart leave webs, and the part "
                   "stays in the sheet": (0, 1, 3),
                   "{}: {} = {} mm: {} takes {} hits, more than the {} one program may have; raise the pitch": (0, 1),
                   "{}: {}: the cut contour is {} x {} mm and reaches {} mm from the program's origin, beyond the {} "
                   "mm the turret punch control addresses": (0,),
                   "the flat pattern of {}": (0,), "piece {} of {} = {} mm": (1,)}
# Templates one of whose values is itself a message with a template of its own (its position).
NESTED = {"{}: {} = {} mm: {} takes {} hits, more than the {} one program may have; raise the pitch": (3,),
          "{}: {}: the cut contour is {} x {} mm and reaches {} mm from the program's origin, beyond the {} "
          "mm the turret punch control addresses": (1,)}


# English template (the f-string with {} for each value) -> Japanese ({0}, {1} ... in any order).
MESSAGE_TEMPLATES = {
    # turret punch on the sheet (issue 26)
    '{}: {} is not a number of mm (give clamp centres like "200, 700")':
        '{0}：{1} は mm の数値ではありません（クランプ中心を "200, 700" のように指定してください）',
    "{}: {} is not a position on the sheet": "{0}：{1} は板材上の位置ではありません",
    '{}: give two numbers "X,Y" in mm, got {}': '{0}：2つの数値 "X,Y"（mm）を指定してください（指定値 {1}）',
    '{}: give two finite numbers "X,Y" in mm, got {}': '{0}：有限な2つの数値 "X,Y"（mm）を指定してください（指定値 {1}）',
    "lines must be (first hit, last hit) pairs of (x, y), got shape {}":
        "線は (x, y) の（最初の打ち抜き、最後の打ち抜き）の組で与えてください（形状 {0}）",
    "line {} is {} mm long, shorter than the {} mm output resolution": "線 {0} の長さは {1} mm で、出力分解能 {2} mm より短いです",
    "{} lines do not fit sequence numbers N001..N999": "{0} 本の線はシーケンス番号 N001〜N999 に収まりません",
    "micro-joints: {} joint(s) do not fit: line {} of the cut contour, among the longest, is {} mm, and {} joint(s) on "
    "it need {} mm (each the {} mm web, a punch diameter of {} mm either side and to the corners); give fewer joints":
        "ミクロジョイント：{0} 個のジョイントが収まりません。切断輪郭の最長の線の一つ、線 {1} は {2} mm で、その上の {3} 個の"
        "ジョイントには {4} mm が必要です（各 {5} mm の継ぎ、その両側と角までパンチ径 {6} mm）。ジョイントを減らしてください",
    "lines {} and {} of the cut contour ({} and {} mm) meet at a corner and are no longer than the nibbling pitch {} mm: "
    "their shared corner would be punched twice; give a pitch below {} mm or fewer divisions":
        "切断輪郭の線 {0} と {1}（{2} mm と {3} mm）は角で接し、どちらもニブリングピッチ {4} mm 以下です。共有する角が"
        "2回打ち抜かれます。ピッチを {5} mm 未満にするか、分割数を減らしてください",
    "micro-joints: the count must be a whole number 0..{}, got {}": "ミクロジョイント：数は 0〜{0} の整数にしてください（指定値 {1}）",
    "micro-joint width must be a number > 0 (mm), got {}": "ミクロジョイントの幅は0より大きい数（mm）にしてください（指定値 {0}）",
    "segment {} of the cut contour is {} mm long, shorter than the {} mm the NC words resolve":
        "切断輪郭の線分 {0} の長さは {1} mm で、NCワードの分解能 {2} mm より短いです",
    "machine profile {} says no sheet size (sheet max): the part cannot be placed":
        "機械プロファイル {0} に板材の大きさ（最大板材）がありません。部品を配置できません",
    # the machine profile (toolpath/ir/machine.py, the posts' frames, operators/exporting.py)
    "Machine & Stock: Machine {} is a {} machine and the {} post writes {} programs; pick a {} machine or Post's Machine":
        "機械と素材：機械 {0} は {1} 用の機械で、{2} ポストは {3} 用のプログラムを書きます。{4} 用の機械か「ポストの既定の機械」を選んでください",
    "Engrave: Safe Z 0 takes the machine's Clearance Height, {} mm, below the Clearance Plane {} mm: give Safe Z, lower the Clearance Plane or raise the machine's Clearance Height":
        "彫刻：安全高さ Z が 0 のときは機械の逃げ高さ {0} mm を使いますが、これはクリアランス高さ {1} mm より低い値です。安全高さ Z を指定するか、クリアランス高さを下げるか、機械の逃げ高さを上げてください",
    "line {}: G53 moves in machine coordinates, which the reader does not know (only a Z lift is followed): {}":
        "{0}行目：G53 は機械座標での移動で、読み込み側はその位置を知りません（Zの上昇だけを扱います）：{1}",
    "Machine & Stock: Clearance Height = {} mm is above Z Reach = {} mm":
        "機械と素材：逃げ高さ = {0} mm が Zの届く高さ = {1} mm を超えています",
    "{}: Tool Change = {}: this post writes {} tool changes only":
        "{0}：工具交換 = {1}：このポストが書ける工具交換は {2} だけです",
    "{} spindle speed S {} is above the {} rpm of the machine {} (machine setting Max Spindle)":
        "{0} 主軸回転数 S {1} が機械 {3} の {2} rpm を超えています（機械の設定「最高主軸回転」）",
    "{} feed {} mm/min is above the {} mm/min of the machine {} (machine setting Max Feed)":
        "{0} 送り {1} mm/min が機械 {3} の {2} mm/min を超えています（機械の設定「最大送り」）",
    "{}: Retract = {} is not a move this control has; choose {}":
        "{0}：Z退避 = {1} はこの制御装置にない動作です。{2} を選んでください",
    "{} {} mm is above the {} mm the machine {} reaches above the work zero (machine setting Z Reach); lower it or "
    "raise Z Reach if the machine really reaches it":
        "{0} {1} mm が、機械 {3} がワーク原点から届く {2} mm を超えています（機械の設定「Zの届く高さ」）。"
        "下げるか、機械が本当に届くなら「Zの届く高さ」を上げてください",
    "the program spans {} mm along {} (from {} to {}), more than the {} mm {} travel of the machine {} (machine "
    "setting Travel {})":
        "プログラムは {1} 方向に {0} mm（{2} から {3} まで）にわたり、機械 {6} の {5} ストローク {4} mm を超えています"
        "（機械の設定「ストローク {7}」）",
    "the program lifts Z to {} mm above the work zero, higher than the {} mm the machine {} reaches (machine "
    "setting Z Reach)":
        "プログラムはZをワーク原点から {0} mm まで上げ、機械 {2} が届く {1} mm を超えています（機械の設定「Zの届く高さ」）",
    # turn-mill: the machine profile, faces not machined, what the control cannot take (post/capacity.py)
    "{} {}: {} is not a turn-mill; the turn-mill presets are {}":
        "{0} {1}：{2} は複合加工機ではありません。複合加工機のプリセットは {3} です",
    "block time must be a number > 0 (ms), got {}": "ブロック処理時間は 0 より大きい数（ms）にしてください（指定値 {0}）",
    "not machined: {} (neither the radial nor the axial tool reaches it)":
        "未加工：{0}（径方向・軸方向のどちらの工具も届きません）",
    "{} is {} kB, larger than the {} kB program memory of {}: run it from a memory card or DNC, or split it":
        "{0} は {1} kB で、{3} のプログラムメモリ {2} kB を超えています。メモリカードか DNC で運転するか、分割してください",
    "{} has {} inverse-time blocks shorter than the {} ms {} takes to process a block (first on line {}): the feed "
    "drops there":
        "{0} には、{3} が1ブロックの処理にかかる {2} ms より短い逆時間送りのブロックが {1} 個あります"
        "（最初は {4} 行目）。そこで送りが落ちます",
    "the design is flat (Z {} mm everywhere) and no stock stands above it: nothing to carve (Stock Above in the Carve panel gives the stock)":
        "デザインが平ら（どこも Z {0} mm）で、その上に素材がありません。削るものがありません（素材は曲面加工パネルの「上面の余肉」で与えます）",
    "{}: a path relative to the .blend file ('//') needs the .blend saved first":
        "{0}：.blend ファイルからの相対パス（//）を使うには、先に .blend を保存してください",
    "--nc {}: line {} turns the C axis; give --rotary c to simulate the part turning with it":
        "--nc {0}：{1}行目でC軸が回ります。部品の回転ごとシミュレーションするには --rotary c を指定してください",
    "{}: the export gate simulates every program before writing it, and cannot on this job's stock even at {} mm: {}":
        "{0}：書き出しゲートはすべてのプログラムをシミュレーションしてから書き出しますが、このジョブの素材では {1} mm でもできません：{2}",
    "pocket {}: the toolpath would have {} points (more than {}) at a spacing of {} mm and a step down of {} mm: give a coarser spacing or step down":
        "ポケット {0}：ツールパスが {1} 点になります（上限 {2} 超、間隔 {3} mm、切込み深さ {4} mm）。間隔か切込み深さを粗くしてください",
    "the roughing would need more than {} moves ({} levels {} mm apart through {} mm of stock): give a larger step down or roughing stepover, or less stock above the design":
        "荒削りには {0} を超える移動が必要です（{3} mm の素材を {2} mm 間隔で {1} 層）。切込み深さか荒削りのステップオーバーを大きくするか、デザイン上の素材を減らしてください",
    "the {} finishing alone would need more than {} tool positions: give a coarser tolerance or sample spacing":
        "{0}仕上げだけで {1} を超える工具位置が必要です。許容差かサンプル間隔を粗くしてください",
    "the {} roughing would need more than {} tool positions ({} layers of {} mm so far): {}; give a stock closer to the part":
        "{0}荒削りには {1} を超える工具位置が必要です（ここまで {3} mm の層が {2} 層）：{4}。部品に近い素材にしてください",
    "the stock's radius {} mm stands up to {} mm outside the part": "素材の半径 {0} mm は部品の外側に最大 {1} mm はみ出しています",
    "the stock's end face Z {} stands {} mm above the part": "素材の端面 Z {0} は部品より {1} mm 上にあります",
    "{}: corner P{} ({}, {}, {}) is outside the allowed range {}": "{0}：角 P{1}（{2}, {3}, {4}）が許容範囲 {5} の外です",
    "{} is empty: give the folder to write into": "{0} が空です。書き出すフォルダーを指定してください",
    "plate {} reaches {} mm from the world origin (more than {} mm) at the scene's unit scale of {} m per unit: is the unit scale right?":
        "板材 {0} がワールド原点から {1} mm まで達しています（{2} mm 超、シーンの単位スケールは1単位 {3} m）。単位スケールは正しいですか",
    "plate {} is tilted {} deg about {}: apply or clear its rotation (Ctrl-A)":
        "板材 {0} が {2} 軸まわりに {1} 度傾いています。回転を適用するか解除してください（Ctrl-A）",
    "object {} is tilted {} deg about {} out of the plate's top: apply or clear its rotation (Ctrl-A)":
        "オブジェクト {0} が {2} 軸まわりに {1} 度、板材の上面から傾いています。回転を適用するか解除してください（Ctrl-A）",
    "collection instance {} is tilted {} deg about {}: clear its rotation about X and Y":
        "コレクションインスタンス {0} が {2} 軸まわりに {1} 度傾いています。X と Y まわりの回転を解除してください",
    "collection instance {} shows no Text, curve or mesh object":
        "コレクションインスタンス {0} はテキスト・カーブ・メッシュのオブジェクトを表示していません",
    "plate {} is {} mm at the scene's unit scale of {} m per unit, larger than the {} mm {} travel of any machine preset: check Scene > Units (Unit Scale) or the plate's size":
        "板材 {0} はシーンの単位スケール（1単位 {2} m）で {1} mm あり、どの機械プリセットの {4} 軸ストローク {3} mm "
        "よりも大きいです。シーン > 単位（単位スケール）か板材の大きさを確認してください",
    "plate {} is {} mm at the scene's unit scale of {} m per unit, larger than the {} mm {} travel of the machine {}: check Scene > Units (Unit Scale), the plate's size or Machine & Stock's Travel":
        "板材 {0} はシーンの単位スケール（1単位 {2} m）で {1} mm あり、機械 {5} の {4} 軸ストローク {3} mm "
        "より大きいです。シーン > 単位（単位スケール）、板材の大きさ、または「機械と素材」のストロークを確認してください",
    "collection instance {} shows no mesh object": "コレクションインスタンス {0} はメッシュオブジェクトを表示していません",
    "design {} is {} mm at the scene's unit scale of {} m per unit, larger than the {} mm {} travel of any machine preset: check Scene > Units (Unit Scale) or the design's size":
        "デザイン {0} はシーンの単位スケール（1単位 {2} m）で {1} mm あり、どの機械プリセットの {4} 軸ストローク {3} mm "
        "よりも大きいです。シーン > 単位（単位スケール）かデザインの大きさを確認してください",
    "--tool {}: {} {} mm is outside the allowed range {}": "--tool {0}：{1} {2} mm が許容範囲 {3} の外です",
    "{} {}: the mesh reaches {} mm from the origin (more than {} mm): is it in other units?":
        "{0} {1}：メッシュが原点から {2} mm まで達しています（{3} mm 超）。単位が違っていませんか",
    "--mesh {}: {}": "メッシュファイル --mesh {0}：{1}",
    "--surface {}: {}": "板面のメッシュファイル --surface {0}：{1}",
    "the design mesh reaches {} mm from the work zero (more than {} mm): is it in other units?":
        "デザインメッシュがワーク原点から {0} mm まで達しています（{1} mm 超）。単位が違っていませんか",
    "the design mesh has a face with a vertex index outside 0..{}": "デザインメッシュに頂点番号が 0..{0} の範囲外の面があります",
    "the design mesh has {} vertices, fewer than one triangle needs (an empty or unreadable mesh file?)":
        "デザインメッシュの頂点が {0} 個で、三角形1つにも足りません（空のファイルか読めないファイルではありませんか）",
    "{}: the export gate simulates every program on a {} mm grid before writing it, and cannot on this job's stock: {}":
        "{0}：書き出しゲートはすべてのプログラムを {1} mm の格子でシミュレーションしてから書き出しますが、このジョブの素材ではできません：{2}",
    "#{} SI_UNIT: a length unit in {}, not in metres": "#{0} SI_UNIT：長さの単位が {1} です（メートルではありません）",
    "#{} SI_UNIT: {} is not an SI prefix": "#{0} SI_UNIT：{1} はSI接頭辞ではありません",
    "#{} CONVERSION_BASED_UNIT '{}': its conversion factor is given in itself":
        "#{0} CONVERSION_BASED_UNIT '{1}'：換算係数がそれ自身の単位で与えられています",
    "#{} CONVERSION_BASED_UNIT '{}': a length unit of {} mm": "#{0} CONVERSION_BASED_UNIT '{1}'：長さの単位が {2} mm です",
    "#{} CONVERSION_BASED_UNIT '{}': no conversion factor, and not a unit Kezuri knows by name ({})":
        "#{0} CONVERSION_BASED_UNIT '{1}'：換算係数がなく、Kezuriが名前で分かる単位（{2}）でもありません",
    "#{} RECTANGULAR_CLOSED_PROFILE: {} {} mm is negative": "#{0} RECTANGULAR_CLOSED_PROFILE：{1} {2} mm が負です",
    "--order: #{} is given more than once in {}; each workingstep is cut once, in the order given":
        "--order：#{0} が {1} に2回以上あります。各ワーキングステップは指定した順に1回ずつ削ります",
    "{}: workingstep #{}: an instance number above {} cannot be listed in the workplan; renumber the file":
        "{0}：ワーキングステップ #{1}：{2} を超えるインスタンス番号は作業計画の一覧に載せられません。ファイルの番号を振り直してください",
    "#{} {}: {} {} is not a coordinate (at most {} mm from the origin)":
        "#{0} {1}：{2} {3} は座標として使えません（原点から {4} mm 以内にしてください）",
    "--nc {}: {}": "NCファイル --nc {0}：{1}",
    "elbow piece {} of {}: {}": "エルボのピース {0}/{1}：{2}",
    "{}: the {} post does not write M19 before a tool change; pick a Fanuc post or switch it off":
        "{0}：{1} ポストは工具交換の前に M19 を書きません。Fanucポストを選ぶか、オフにしてください",
    "a {} mm cell gives {} dexels round the bar (more than {}); use a coarser cell":
        "{0} mm のセルでは丸棒の周りが {1} 個のデクセル（上限 {2} 超）になります。セルを粗くしてください",
    'Kezuri internal error ({}): {}; details in the system console': 'Kezuriの内部エラー（{0}）：{1}。詳細はシステムコンソールを見てください',
    'scene unit scale must be positive, got {}': 'シーンの単位スケールは正の値にしてください（指定値 {0}）',
    'object {} ({}) has no geometry': 'オブジェクト {0}（{1}）に形状がありません',
    'object {} has no outline (no faces and no edges)': 'オブジェクト {0} に輪郭がありません（面も辺もありません）',
    'object {} has an open or branching outline near ({}, {}, {}): close it (or fill the curve)':
        'オブジェクト {0} の輪郭が ({1}, {2}, {3}) 付近で開いているか分岐しています。閉じてください（またはカーブを塗りつぶしてください）',
    'object {} is a {}; use a Text, curve or mesh': 'オブジェクト {0} は {1} です。テキスト・カーブ・メッシュを使ってください',
    'object {} has a vertex with a non-finite coordinate': 'オブジェクト {0} に有限でない座標の頂点があります',
    'plate {} must be a mesh object, not a {}': '板材 {0} はメッシュオブジェクトにしてください（{1} ではなく）',
    'plate {} has no faces': '板材 {0} に面がありません',
    'plate {} has a vertex with a non-finite coordinate': '板材 {0} に有限でない座標の頂点があります',
    'object {} cannot be turned into a mesh: {}': 'オブジェクト {0} をメッシュに変換できません：{1}',
    'unknown work origin {}': '不明なワーク原点 {0}',
    'Engraving planned: {} moves, about {} min': '彫刻パスを作成しました：{0} 移動、約 {1} 分',
    'Wrote {}': '{0} を書き出しました',
    '{} is a {}; the {}ing tool must be a {}': '{0} は {1} です。{2}用の工具は {3} にしてください',
    'pocket {}: the outline must be one closed loop, found {}': 'ポケット {0}：輪郭は閉じたループ1つにしてください（{1} 個あります）',
    '{} pockets planned; estimated cycle time {} min {} s': '{0} 個のポケットを作成しました。加工時間の見積り {1} 分 {2} 秒',
    '{} object(s) {} pockets': '{0} 個のオブジェクト：ポケット指定を変更しました（{1}）',
    'object {}: select exactly one quad face (found {} face(s), the first with {} corners)':
        'オブジェクト {0}：四角形の面を1つだけ選択してください（{1} 面あり、最初の面の頂点数 {2}）',
    'Unfolded into {} triangles; edges {} mm': '{0} 個の三角形に展開しました。辺の長さ {1} mm',
    'Read the quad from {}': '{0} から四辺形を読み込みました',
    'Elbow of {} pieces, {} deg each': '{0} ピースのエビ管、1ピース {1} 度',
    'no simulation for {}': '{0} のシミュレーションはありません',
    'Removed {} cm^3 in {} s; {} finding(s)': '{0} cm^3 を除去しました（{1} 秒）。指摘 {2} 件',
    'the imported ISO 14649 file is gone: {}': '読み込んだISO 14649ファイルが見つかりません：{0}',
    'pocket {}: the outline must be one closed loop': 'ポケット {0}：輪郭は閉じたループ1つにしてください',
    '{} workingsteps from {}': '{1} から {0} 個のワーキングステップ',
    '{} operations, about {} min': '{0} 工程、約 {1} 分',
    'part {} has no faces': '部品 {0} に面がありません',
    'part {}: no faces are selected (select them in Edit Mode, or switch off Selected Faces Only)':
        '部品 {0}：面が選択されていません（編集モードで選択するか、「選択面のみ」をオフにしてください）',
    'unknown post {}; choose one of {}': '不明なポスト {0}。{1} から選んでください',
    '{}: {} {} is outside the {}..{} the control accepts ({})':
        '{0}：{1} {2} は制御装置が受け付ける範囲 {3}..{4} の外です（{5}）',
    '{} must be a finite number {}, got {}': '{0} は有限の数値（{1}）にしてください（指定値 {2}）',
    'the turret punch writes a PunchProgram (lines of hits), got {}': 'タレットパンチが書くのは PunchProgram（パンチ線の列）です（指定：{0}）',
    'punch program {}: its operations must be one or more PunchOperations': 'パンチプログラム {0}：操作は1つ以上の PunchOperation にしてください',
    'G92 origin must be two numbers (x, y), got {}': 'G92 の原点は2つの数値 (x, y) にしてください（指定値 {0}）',
    '{} must be a finite number > 0, got {}': '{0} は0より大きい有限の数値にしてください（指定値 {1}）',
    'tool side must be one of {}, got {}': '工具の側は {0} のいずれかにしてください（指定値 {1}）',
    'turret station must be an integer 1..999, got {}': 'タレットステーションは1〜999の整数にしてください（指定値 {0}）',
    'end code must be one of {}, got {}': '終了コードは {0} のいずれかにしてください（指定値 {1}）',
    'operation {}: lines must be (first hit, last hit) pairs of (x, y)': '操作 {0}：線は (x, y) の（最初の打点、最後の打点）の組にしてください',
    'operation {}: compensation must be one of {}, got {}': '操作 {0}：工具補正は {1} のいずれかにしてください（指定値 {2}）',
    'G79 punching line: pitch Q {} must be at least the thickness {} mm': 'G79 パンチング直線：ピッチ Q {0} は板厚 {1} mm 以上にしてください',
    '{} must be a number, got {}': '{0} は数値にしてください（指定値 {1}）',
    'operation {} has arc moves; the CL data writer writes GOTO points only': '工程 {0} に円弧移動があります。CLデータ出力は GOTO 点のみです',
    'operation {} moves rotary axes {} without a tool direction; the CL data writer knows X-Z-C turn-mill and 3-axis operations':
        '工程 {0} は工具方向なしで回転軸 {1} を動かします。CLデータ出力が扱えるのは X-Z-C 複合加工と3軸の工程です',
    'operation {}: the macro post knows only the gouge texture': '工程 {0}：マクロポストが扱えるのは彫刻刀跡テクスチャだけです',
    'operation {}: O7023 splits X moves only; set the raster angle to 0 or use the baked Fanuc post':
        '工程 {0}：O7023 が分割できるのは X 方向の移動だけです。ラスター角度を0にするか、展開済みFanucポストを使ってください',
    'operation {}: scoop motion and spacing jitter exist only in baked programs; use the baked Fanuc post':
        '工程 {0}：すくい動作と間隔のゆらぎは展開済みプログラムにしかありません。展開済みFanucポストを使ってください',
    'bend lines must be a (k, 2, 2) array, got {}': '曲げ線は (k, 2, 2) の配列にしてください（指定値 {0}）',
    'margin must be >= 0, got {}': '余白は0以上にしてください（指定値 {0}）',
    '{} {}: a contour must be a (k, 2) array with k >= 2, got {}': '{0} {1}：輪郭は k >= 2 の (k, 2) 配列にしてください（指定値 {2}）',
    '{} {}: non-finite coordinate': '{0} {1}：有限でない座標があります',
    'operation {} still carries an unbaked texture: bake it first (the {} post writes the cut depths literally)':
        '工程 {0} のテクスチャがまだ展開されていません。先に展開してください（{1} ポストは切込み深さをそのまま書き出します）',
    'the {} post is for 3-axis milling; operation {} moves rotary axes {}': '{0} ポストは3軸フライス用です。工程 {1} は回転軸 {2} を動かします',
    'unknown rotary post {}; choose one of {}': '不明な回転テーブルポスト {0}。{1} から選んでください',
    '{} carries a texture; the {} post writes C-X-Z pockets only': '{0} にはテクスチャがあります。{1} ポストが書き出すのは C-X-Z ポケットだけです',
    '{}: the {} post needs C positions for every move (got rotary axes {}); plan it with toolpath.operations.rotary.rotary':
        '{0}：{1} ポストにはすべての移動の C 位置が必要です（回転軸 {2}）。toolpath.operations.rotary.rotary で作成してください',
    '{} has arcs; a C-X-Z machine cuts straight X/C/Z moves only': '{0} に円弧があります。C-X-Z 機は X/C/Z の直線移動しか削れません',
    '{}: X must stay on the negative side of the rotation centre (X = -R)': '{0}：X は回転中心の負側（X = -R）にしてください',
    '{}: the machine has no Y axis; Y must be 0': '{0}：この機械にY軸はありません。Y は0にしてください',
    'operation {} is not an X-Z-C turn-mill operation (it has no radial/axial tool direction): plan it with toolpath.operations.turnmill.turnmill':
        '工程 {0} は X-Z-C 複合加工の工程ではありません（径方向・軸方向の工具方向がありません）。toolpath.operations.turnmill.turnmill で作成してください',
    'operation {} has arc moves; the {} post writes straight moves only': '工程 {0} に円弧移動があります。{1} ポストは直線移動しか書き出しません',
    'gouge motion must be one of {}, got {}': '彫り動作は {0} のいずれかにしてください（指定値 {1}）',
    'stepover {} mm is wider than the {} mm roughing tool: ridges would be left standing':
        'ステップオーバー {0} mm が荒加工工具 {1} mm より広いため、削り残しの山ができます',
    'letter clearance {} mm is less than the roughing tool radius {} mm: the ball would cut into the letters':
        '文字との逃げ {0} mm が荒加工工具の半径 {1} mm より小さいため、ボールが文字に食い込みます',
    'the {} mm finishing tool is wider than the {} mm band': '仕上げ工具 {0} mm が帯の幅 {1} mm より広いです',
    'letters {} reach outside the plate': '文字 {0} が板材の外にはみ出しています',
    'texture {} must be a finite number': 'テクスチャの {0} は有限の数値にしてください',
    '{} must be a finite number, got {}': '{0} は有限の数値にしてください（指定値 {1}）',
    '{} must be greater than zero, got {}': '{0} は0より大きくしてください（指定値 {1}）',
    '--tool {}: give ball:D, flat:D or bull:D,R': '--tool {0}：ball:D、flat:D、bull:D,R のいずれかで指定してください',
    'line {}: unbalanced parenthesis in {}': '{0} 行目：{1} の括弧が対応していません',
    'line {}: no G-code words in {}': '{0} 行目：{1} にGコードのワードがありません',
    'line {}: R-format arcs are not supported; use I and J': '{0} 行目：R 指定の円弧には対応していません。I と J を使ってください',
    'line {}: a move before any G0/G1/G2/G3': '{0} 行目：G0/G1/G2/G3 より前に移動があります',
    'line {}: an arc needs I and J': '{0} 行目：円弧には I と J が必要です',
    'tool kind {} is not one of {}': '工具の種類 {0} は {1} のいずれでもありません',
    'tool diameter must be a positive number, got {}': '工具径は正の数にしてください（指定値 {0}）',
    'tool number must be an integer 0..999, got {}': '工具番号は0〜999の整数にしてください（指定値 {0}）',
    'corner radius {} does not fit a {} mm tool': 'コーナー半径 {0} は {1} mm の工具に収まりません',
    'operation {}: move arrays have different lengths': '工程 {0}：移動の配列の長さが揃っていません',
    'operation {}: unknown move kind': '工程 {0}：不明な移動の種類です',
    'operation {}: move {} has a non-finite coordinate': '工程 {0}：移動 {1} に有限でない座標があります',
    'operation {}: cutting move {} has no positive feed': '工程 {0}：切削移動 {1} に正の送り速度がありません',
    'operation {}: an arc has no centre': '工程 {0}：円弧に中心がありません',
    'operation {}: spindle speed must be >= 0': '工程 {0}：主軸回転数は0以上にしてください',
    'operation {}: rotary axis {} has {} values for {} moves': '工程 {0}：回転軸 {1} の値が {2} 個ありますが、移動は {3} 個です',
    'operation {}: rotary axis {} has a non-finite value': '工程 {0}：回転軸 {1} に有限でない値があります',
    'operation {}: texture must be a GougeTexture or None, got {}':
        '工程 {0}：テクスチャは GougeTexture か None にしてください（指定は {1}）',
    'line {}: cannot read {}': '{0} 行目：{1} を読めません',
    'line {}: expected one G or M code, got {}': '{0} 行目：GコードかMコードを1つ書いてください（{1}）',
    'the lines give different tool diameters {}: one punch is simulated': '行ごとに工具径が異なります {0}。シミュレーションできるパンチは1本です',
    'punch diameter must be a number > 0, got {}': 'パンチ径は0より大きい数にしてください（指定値 {0}）',
    "punch diameter {} does not match the program's P {}": 'パンチ径 {0} がプログラムの P {1} と一致しません',
    'tolerance must be > 0 and well under the punch radius, got {}': '許容差は0より大きく、パンチ半径より十分小さくしてください（指定値 {0}）',
    'line {}: {} given twice in {}': '{0} 行目：{2} に {1} が2回あります',
    'line {}: {} comes after the program end': '{0} 行目：{1} がプログラム終了の後にあります',
    'line {}: {} is not a turret-punch code this reader knows (G92, G72, G69, G79, G50, M30)':
        '{0} 行目：{1} はこの読み込みが扱うタレットパンチのコード（G92, G72, G69, G79, G50, M30）ではありません',
    'line {}: {} needs {}, got {}': '{0} 行目：{1} には {2} が必要です（{3}）',
    'line {}: a number is not finite in {}': '{0} 行目：{1} に有限でない数値があります',
    'line {}: {} takes no words, got {}': '{0} 行目：{1} にワードは付けられません（{2}）',
    'line {}: {} before any G72 reference point': '{0} 行目：G72 の基準点より前に {1} があります',
    'line {}: I (length) must be >= 0 and Q (pitch) > 0, got {}': '{0} 行目：I（長さ）は0以上、Q（ピッチ）は0より大きくしてください（{1}）',
    'line {}: D (thickness) must be > 0, got {}': '{0} 行目：D（板厚）は0より大きくしてください（{1}）',
    'operation {}: radial turn-mill moves are straight in X, Z and C, not G2/G3 arcs':
        '工程 {0}：複合加工の径方向の移動は X・Z・C の直線で、G2/G3 の円弧ではありません',
    '{}: an outline must be a list of (x, y) points': '{0}：輪郭は (x, y) 点のリストにしてください',
    '{}: outline has a non-finite coordinate (NaN or infinity)': '{0}：輪郭に有限でない座標（NaN または無限大）があります',
    '{}: outline has fewer than 3 distinct points': '{0}：輪郭の異なる点が3つ未満です',
    '{}: outline encloses no area': '{0}：輪郭が面積を囲んでいません',
    '{}: no closed outline': '{0}：閉じた輪郭がありません',
    '{}: no faces with an area when seen from above': '{0}：上から見て面積のある面がありません',
    'stepover must be a positive number, got {}': 'ステップオーバーは正の数にしてください（指定値 {0}）',
    '{} raster rows ({} mm at a {} mm stepover): more than {}':
        'ラスター行が {0} 行（{1} mm をステップオーバー {2} mm で）あり、上限 {3} を超えます',
    'pocket names must be unique, got {}': 'ポケット名が重複しています：{0}',
    'allowance must be >= 0, got {}': '削り代は0以上にしてください（指定値 {0}）',
    'the rotary pockets are cut with a ball-nose bit, not a {} tool': '回転テーブルポケットはボールエンドミルで削ります（{0} ではなく）',
    '{}: the outline crosses itself': '{0}：輪郭が自己交差しています',
    '{}: depth must be greater than zero, got {}': '{0}：深さは0より大きくしてください（指定値 {1}）',
    '{}: depth {} mm goes through the {} mm board': '{0}：深さ {1} mm が板厚 {2} mm を貫通します',
    "{}: depth {} mm is beyond the bit's flute length {} mm": '{0}：深さ {1} mm が刃長 {2} mm を超えています',
    '{}: wall angle must be 0..{} degrees from vertical, got {}': '{0}：壁の角度は垂直から0〜{1}度にしてください（指定値 {2}）',
    '{}: bottom must be one of {}, got {}': '{0}：底の形は {1} のいずれかにしてください（指定値 {2}）',
    '{}: the outline reaches outside the {} x {} mm board': '{0}：輪郭が {1} x {2} mm の板の外にはみ出しています',
    'board sizes must be positive numbers, got {}': '板の寸法は正の数にしてください（指定値 {0}）',
    '{} {} mm is wider than the {} mm bit: ridges would be left standing': '{0} {1} mm が刃物 {2} mm より広いため、削り残しの山ができます',
    '{}: {} must be a finite number, got {}': '{0}：{1} は有限の数値にしてください（指定値 {2}）',
    '{}: the centre must be two finite numbers, got {}': '{0}：中心は有限の数値2つにしてください（指定値 {1}）',
    '{}: a spherical bowl needs a finite sphere radius, got {}': '{0}：球面の器には有限の球半径が必要です（指定値 {1}）',
    '{}: a spherical bowl has a vertical rim; set the wall angle to 0': '{0}：球面の器の縁は垂直です。壁の角度を0にしてください',
    "{}: the bowl's lowest point (the centre) is outside the outline": '{0}：器の最も低い点（中心）が輪郭の外にあります',
    '{}: sphere radius {} mm is smaller than the opening requires: a bowl {} mm deep reaching {} mm from its centre needs at least {} mm':
        '{0}：球半径 {1} mm は開口部に対して小さすぎます。深さ {2} mm で中心から {3} mm まで届く器には {4} mm 以上が必要です',
    'pockets {} and {} overlap ({} mm^2)': 'ポケット {0} と {1} が重なっています（{2} mm^2）',
    'a stock box needs six numbers (x0, y0, z0, x1, y1, z1), got {}':
        '素材の直方体には6つの数値 (x0, y0, z0, x1, y1, z1) が必要です（{0} 個）',
    'a {} mm cell gives {} x {} cells over the stock (more than {}); use a coarser cell':
        '{0} mm のセルでは素材が {1} x {2} セル（上限 {3} 超）になります。セルを粗くしてください',
    'kernel must be one of {}, got {}': 'カーネルは {0} のいずれかにしてください（指定値 {1}）',
    'the {} is not available: {}': '{0} は使えません：{1}',
    'engine must be one of {}, got {}': 'エンジンは {0} のいずれかにしてください（指定値 {1}）',
    'chunk must be a positive number of triangles, got {}': 'チャンクは正の三角形数にしてください（指定値 {0}）',
    'stock box needs six finite numbers, got {}': '素材の直方体には有限の数値6つが必要です（指定値 {0}）',
    'stock box ({}, {}, {})..({}, {}, {}) encloses no volume: every max must be above its min':
        '素材の直方体 ({0}, {1}, {2})..({3}, {4}, {5}) に体積がありません。最大値はすべて最小値より大きくしてください',
    'stock cylinder top must be a finite number, got {}': '素材の円柱の上面は有限の数値にしてください（指定値 {0}）',
    'stock must be a BoxStock, a CylinderStock or (x0, y0, z0, x1, y1, z1), got {}':
        '素材は BoxStock、CylinderStock、または (x0, y0, z0, x1, y1, z1) にしてください（指定値 {0}）',
    'not an Operation: {}': '工程（Operation）ではありません：{0}',
    'operation {}: start point has a non-finite coordinate': '工程 {0}：開始点に有限でない座標があります',
    'operation {}: rotary axes {} are not simulated (only C, a table turning about Z)':
        '工程 {0}：回転軸 {1} はシミュレーションできません（Z軸まわりに回るテーブルの C のみ）',
    'travel limits: unknown axis {} (use x, y, z, c)': 'ストローク制限：不明な軸 {0}（x, y, z, c を使ってください）',
    'travel limits for {}: need finite (min, max) with min <= max, got {}':
        '{0} のストローク制限：min <= max の有限な (min, max) が必要です（指定値 {1}）',
    '{} must be a positive number of mm, got {}': '{0} は正の mm 値にしてください（指定値 {1}）',
    'operation {}: radial turn-mill work is simulated for ball end mills, not a {}':
        '工程 {0}：複合加工の径方向加工でシミュレーションできるのはボールエンドミルです（{1} ではなく）',
    'stock cylinder {} must be a positive number, got {}': '素材の円柱の {0} は正の数にしてください（指定値 {1}）',
    'an ISO 14649 file needs exactly one PROJECT, this one has {}':
        'ISO 14649 ファイルには PROJECT がちょうど1つ必要です（このファイルは {0} 個）',
    '#{} GENERAL_CLOSED_PROFILE: the outline #{} is not closed (its last point is not its first)':
        '#{0} GENERAL_CLOSED_PROFILE：輪郭 #{1} が閉じていません（最後の点が最初の点と一致しません）',
    '#{} {}: attribute {} (number {}) is missing; the instance has {} attributes':
        '#{0} {1}：属性 {2}（{3} 番目）がありません。このインスタンスの属性は {4} 個です',
    '#{} {}: attribute {} is unset ($) but required': '#{0} {1}：属性 {2} が未設定（$）ですが必須です',
    '#{} {}: attribute {} must refer to {}, found the value {}': '#{0} {1}：属性 {2} は {3} を参照する必要がありますが、値 {4} があります',
    '#{} {}: attribute {} refers to #{}, which is not defined': '#{0} {1}：属性 {2} が参照する #{3} は定義されていません',
    '#{} {}: attribute {} must refer to {}, found #{} {}': '#{0} {1}：属性 {2} は {3} を参照する必要がありますが、#{4} {5} です',
    '#{} {}: attribute {} must be a list of references, found {}': '#{0} {1}：属性 {2} は参照のリストにしてください（{3}）',
    '#{} {}: attribute {} must be a number, found {}': '#{0} {1}：属性 {2} は数値にしてください（{3}）',
    '#{} {}: attribute {} must be a {} number, found {}': '#{0} {1}：属性 {2} は {3} の数値にしてください（{4}）',
    '#{} {}: {} {} mm is larger than {} mm': '#{0} {1}：{2} {3} mm が {4} mm より大きいです',
    '#{} {}: attribute {} must be a string, found {}': '#{0} {1}：属性 {2} は文字列にしてください（{3}）',
    '#{} {}: attribute {} must be an enumeration such as .LEFT., found {}':
        '#{0} {1}：属性 {2} は .LEFT. のような列挙値にしてください（{3}）',
    '#{} {}: attribute {} must be .T. or .F., found {}': '#{0} {1}：属性 {2} は .T. か .F. にしてください（{3}）',
    '#{} {}: attribute {} must be 1 to 3 numbers, found {}': '#{0} {1}：属性 {2} は1〜3個の数値にしてください（{3}）',
    '#{} AXIS2_PLACEMENT_3D: ref_direction is parallel to axis': '#{0} AXIS2_PLACEMENT_3D：ref_direction が axis と平行です',
    '#{} TRIMMED_CURVE: attribute {} must be a list, found {}': '#{0} TRIMMED_CURVE：属性 {1} はリストにしてください（{2}）',
    '#{} TRIMMED_CURVE: attribute {} has neither a CARTESIAN_POINT nor a PARAMETER_VALUE: {}':
        '#{0} TRIMMED_CURVE：属性 {1} に CARTESIAN_POINT も PARAMETER_VALUE もありません：{2}',
    '#{} {}: diameter must be positive, found {}': '#{0} {1}：直径は正の値にしてください（{2}）',
    '#{} {}: {} {} mm must be above 0': '#{0} {1}：{2} {3} mm は0より大きくしてください（ISO 14649 の意味）',
    '#{} {}: {} {} mm must be 0 or more': '#{0} {1}：{2} {3} mm は0以上にしてください（取り代は負にできません）',
    '#{} {}: overlap {} must be above 0 and at most 1 (a ratio of the tool diameter)':
        '#{0} {1}：overlap {2} は0より大きく1以下にしてください（工具径に対する比）',
    'workingstep #{}: its name is {} characters; the first {} are used, followed by ...':
        'ワーキングステップ #{0}：名前が {1} 文字あります。先頭の {2} 文字に ... を付けて使います',
    "{}: diameter {} mm is larger than the diameter {} mm of {}; use a tool that fits the feature":
        "{0}：直径 {1} mm が {3} の直径 {2} mm より大きいです。フィーチャに入る工具を使ってください",
    "{}: diameter {} mm is larger than the width {} mm of {}; use a tool that fits the feature":
        "{0}：直径 {1} mm が {3} の幅 {2} mm より大きいです。フィーチャに入る工具を使ってください",
    '#{} WORKPLAN contains itself (through #{})': '#{0} WORKPLAN が（#{1} を通して）自分自身を含んでいます',
    '#{} DIRECTION: direction_ratios are all zero': '#{0} DIRECTION：direction_ratios がすべて0です',
    '#{} TRIMMED_CURVE: attribute {} must hold a CARTESIAN_POINT or a PARAMETER_VALUE, found #{} {}':
        '#{0} TRIMMED_CURVE：属性 {1} は CARTESIAN_POINT か PARAMETER_VALUE にしてください（#{2} {3}）',
    '#{} PLANAR_FACE: the removal boundary #{} runs along the course of travel #{}, so the face has no area':
        '#{0} PLANAR_FACE：除去境界 #{1} が移動経路 #{2} に沿っているため、面に面積がありません',
    '#{} {}: angle must be above 0 and at most 90 degrees, found {}': '#{0} {1}：角度は0度より大きく90度以下にしてください（{2}）',
    '#{} COMPOSITE_CURVE: segment {} starts {} mm away from the end of the previous one':
        '#{0} COMPOSITE_CURVE：セグメント {1} の始点が前のセグメントの終点から {2} mm 離れています',
    'cannot write {} {} as a Part 21 value': '{0} {1} を Part 21 の値として書けません',
    '#{} has no part {} (parts: {})': '#{0} に部分 {1} がありません（部分：{2}）',
    'Part 21 cannot represent the real {}': 'Part 21 では実数 {0} を表せません',
    "bad Part 21 type name {} (upper case letters, digits, '_')": "Part 21 の型名 {0} が不正です（英大文字・数字・'_'）",
    '#{} is {}, not {}': '#{0} は {1} で、{2} ではありません',
    'bad instance id in {}': '{0} のインスタンスIDが不正です',
    'bad enumeration name {}': '列挙名 {0} が不正です',
    'bad instance id {}': 'インスタンスID {0} が不正です',
    'duplicate instance #{}': 'インスタンス #{0} が重複しています',
    '{} was not reserved or is already defined': '{0} は予約されていないか、すでに定義されています',
    'reserved but never defined: {}': '予約されたまま定義されていません：{0}',
    'no instance #{}': 'インスタンス #{0} がありません',
    '#{} refers to #{}, which is not defined': '#{0} が参照する #{1} は定義されていません',
    'complex instance #{} has no parts': '複合インスタンス #{0} に部分がありません',
    'no workingstep #{}': 'ワーキングステップ #{0} がありません',
    '#{} MILLING_TECHNOLOGY: neither spindle nor cutspeed is given':
        '#{0} MILLING_TECHNOLOGY：spindle も cutspeed もありません',
    '#{} MILLING_TECHNOLOGY: no positive feedrate (nor feedrate_per_tooth with a known number of teeth)':
        '#{0} MILLING_TECHNOLOGY：正の feedrate がありません（刃数の分かる feedrate_per_tooth もありません）',
    '#{} MILLING_TECHNOLOGY: spindle speed {} rpm ({}); a cutting operation needs a turning spindle':
        '#{0} MILLING_TECHNOLOGY：主軸回転数 {1} rpm（{2}）；切削には主軸の回転が必要です',
    "#{} MILLING_CUTTING_TOOL '{}': tool_top_angle {} degrees is not a drill point "
    "(0 <= angle < 90, measured from the plane square to the axis)":
        "#{0} MILLING_CUTTING_TOOL '{1}'：tool_top_angle {2} 度はドリルの先端角ではありません"
        "（0 以上 90 未満、軸に直角な面から測る角度）",
    "{} #{} '{}': its {} reaches Z {}, {} mm below the stock bottom (Z {}, {}); "
    "correct the feature depth or the stock":
        "{0} #{1} '{2}'：{3} が Z {4} に達し、素材の底（Z {6}、{7}）より {5} mm 下です；"
        "フィーチャの深さか素材を直してください",
    'plate thickness must be a positive number of mm, got {}':
        '板厚は正の数（mm）でなければなりません：{0}',
    '{} cuts to Z {}, through the {} mm plate (its bottom is Z {}); make the cut shallower than the plate thickness':
        '{0} は Z {1} まで削り、{2} mm の板を貫通します（板の底は Z {3}）；板厚より浅くしてください',
    '#{} MACHINING_WORKINGSTEP: its security plane (Z {}) is not above the feature #{} (Z {})':
        '#{0} MACHINING_WORKINGSTEP：安全平面（Z {1}）がフィーチャー #{2}（Z {3}）より上にありません',
    '{} mm cut {} mm at a time needs {} layers (more than {}): check axial_cutting_depth':
        '{0} mm を {1} mm ずつ削ると {2} 層（上限 {3} 超）になります。axial_cutting_depth を確認してください',
    'stepover {} mm (overlap {}, radial depth {}) is below {} mm':
        'ステップオーバー {0} mm（オーバーラップ {1}、径方向切込み {2}）が {3} mm 未満です',
    'stock box {} has no volume: give (min corner, max corner)': '素材の直方体 {0} に体積がありません。(最小角, 最大角) で指定してください',
    'pockets need an end mill, not a {}': 'ポケットにはエンドミルが必要です（{0} ではなく）',
    'overlap is a ratio of the tool diameter, 0 <= overlap < 1; got {}':
        'オーバーラップは工具径に対する比率で 0 <= overlap < 1 です（指定値 {0}）',
    'ramp angle must be 0..90 degrees, got {}': 'ランプ角は0〜90度にしてください（指定値 {0}）',
    'order must list every workingstep once; missing {}, unknown {}, given {}':
        '順序にはすべてのワーキングステップを1回ずつ並べてください。不足 {0}、不明 {1}、指定 {2}',
    '#{} {}: retract_plane {} must be above the feature (positive)':
        '#{0} {1}：retract_plane {2} はフィーチャーより上（正の値）にしてください',
    'more than {} contour passes at a {} mm stepover': 'ステップオーバー {1} mm では輪郭パスが {0} 回を超えます',
    'planar face #{}: {} facing strokes (more than {}) at a {} mm stepover':
        '平面 #{0}：ステップオーバー {3} mm では正面削りが {1} 回（上限 {2} 超）になります',
    '{} must be a positive number, got {}': '{0} は正の数にしてください（指定値 {1}）',
    'pocket {}: depth {} must be above 0 and at most the stock height {}':
        'ポケット {0}：深さ {1} は0より大きく、素材の高さ {2} 以下にしてください',
    'pocket {}: corner radius must not be negative': 'ポケット {0}：コーナー半径を負にはできません',
    "workingstep #{} '{}': {}": "ワーキングステップ #{0} '{1}'：{2}",
    'more than {} finishing passes at a {} mm stepover': 'ステップオーバー {1} mm では仕上げパスが {0} 回を超えます',
    'vertices must have shape (n, 3), got {}': '頂点の形状は (n, 3) にしてください（{0}）',
    'faces must be triangles, shape (m, 3), got {}': '面は三角形、形状 (m, 3) にしてください（{0}）',
    'face indices must be integers, got {}': '面のインデックスは整数にしてください（{0}）',
    'face indices must lie in 0..{}': '面のインデックスは 0〜{0} の範囲にしてください',
    'the mesh is non-manifold: {} edge(s) are shared by more than two faces': 'メッシュが非多様体です：{0} 本の辺を3つ以上の面が共有しています',
    'sample spacing must be a number > 0, got {}': 'サンプル間隔は0より大きい数にしてください（指定値 {0}）',
    'labels must be {} values from NEITHER, RADIAL, AXIAL, BOTH':
        'ラベルは NEITHER, RADIAL, AXIAL, BOTH のいずれかの値を {0} 個にしてください',
    'stock must be a Stock, got {}': '素材は Stock にしてください（{0}）',
    'the part does not fit in the stock: {} vertices lie outside the {} mm bar from z = {} to {}':
        '部品が素材に収まりません：{0} 個の頂点が z = {2}〜{3} の直径 {1} mm の丸棒の外にあります',
    'stock radius and Z range must be finite numbers, got {}': '素材の半径とZ範囲は有限の数値にしてください（指定値 {0}）',
    'stock radius must be > 0, got {}': '素材の半径は0より大きくしてください（指定値 {0}）',
    'stock z_min ({}) must be below z_max ({})': '素材の z_min（{0}）は z_max（{1}）より下にしてください',
    'the tool radius must be > 0, got a tool diameter of {}': '工具半径は0より大きくしてください（工具径 {0}）',
    'tolerance {} must be smaller than the tool radius {}': '許容差 {0} は工具半径 {1} より小さくしてください',
    'stepover must be > 0 and at most the tool diameter, got {}': 'ステップオーバーは0より大きく工具径以下にしてください（指定値 {0}）',
    'ray chunk size must be a positive integer, got {}': 'レイのチャンクサイズは正の整数にしてください（指定値 {0}）',
    'the ray engine returned {} results for {} rays': 'レイエンジンが {1} 本のレイに対して {0} 個の結果を返しました',
    'operation {}: direction must be one of {}': '工程 {0}：方向は {1} のいずれかにしてください',
    'operation {}: an X-Z-C operation moves exactly the C axis': '工程 {0}：X-Z-C の工程で動かす回転軸は C だけです',
    'operation {}: the machine has no Y axis (Y must be 0)': '工程 {0}：この機械にY軸はありません（Y は0にしてください）',
    '{} must be a number > 0, got {}': '{0} は0より大きい数にしてください（指定値 {1}）',
    'direction must be one of {}, got {}': '方向は {0} のいずれかにしてください（指定値 {1}）',
    '{} must be an integer, got {}': '{0} は整数にしてください（指定値 {1}）',
    '{} must be at least {}, got {}': '{0} は {1} 以上にしてください（指定値 {2}）',
    'a twisted quad needs 4 corners (x, y, z), got an array of shape {}': 'ねじれ四辺形には4つの頂点 (x, y, z) が必要です（配列の形状 {0}）',
    '{} must be an (n+1, 3) array with n >= 1, got shape {}': '{0} は n >= 1 の (n+1, 3) 配列にしてください（形状 {1}）',
    '{} has a non-finite coordinate (NaN or infinity)': '{0} に有限でない座標（NaN または無限大）があります',
    'CDL: a twisted quad needs exactly 4 LINE records, found {} (at lines: {})':
        'CDL：ねじれ四辺形には LINE レコードがちょうど4つ必要です（{0} 個、行：{1}）',
    'CDL line {}: the four LINEs do not close: the loop ends at {}, not at P1 {}':
        'CDL {0} 行目：4本の LINE が閉じていません。ループの終点は {1} で、P1 {2} ではありません',
    'the two rails need the same number of points, got {} and {}': '2本のレールの点の数を揃えてください（{0} と {1}）',
    'diagonal must be one of {}, got {}': '対角線は {0} のいずれかにしてください（指定値 {1}）',
    'an outline must be a (k, 2) array, got shape {}': '輪郭は (k, 2) 配列にしてください（形状 {0}）',
    'outline turns straight back on itself at point {}': '輪郭が点 {0} で真後ろに折り返しています',
    'bend angle KD must be at most 180 degrees, got {}': '曲げ角度 KD は180度以下にしてください（指定値 {0}）',
    'bend radius RT ({}) must exceed the pipe radius D/2 ({})': '曲げ半径 RT（{0}）は管の半径 D/2（{1}）より大きくしてください',
    'a {} degree bend needs more than {} pieces': '{0} 度の曲げには {1} ピースより多く必要です',
    'corners P{}, P{} and P{} are collinear: the edges meeting at P{} lie on one straight line':
        '頂点 P{0}、P{1}、P{2} が一直線上にあります：P{3} で交わる辺が同じ直線上にあります',
    'CDL line {}: LINE record has {} numbers, expected 13 or 14 (x1, y1, z1, x2, y2, z2, colour, type, ...)':
        'CDL {0} 行目：LINE レコードの数値が {1} 個です。13 か 14 個（x1, y1, z1, x2, y2, z2, 色, 線種, ...）が必要です',
    'CDL line {}: LINE has a non-finite coordinate': 'CDL {0} 行目：LINE に有限でない座標があります',
    'CDL line {}: LINE has zero length': 'CDL {0} 行目：LINE の長さが0です',
    'CDL line {}: the LINE ends at {} where {} other LINEs begin or end (a closed loop needs exactly 1)':
        'CDL {0} 行目：LINE の終点 {1} で他の LINE が {2} 本始まるか終わっています（閉じたループにはちょうど1本が必要です）',
    'rung {}: the rails touch (zero-length rung a[{}]-b[{}])': '横桟 {0}：レールが接しています（長さ0の横桟 a[{1}]-b[{2}]）',
    'strip step {}: both rails stand still (rungs {} and {} coincide)': '帯のステップ {0}：両方のレールが進みません（横桟 {1} と {2} が一致）',
    'corners P{} and P{} coincide (zero-length {})': '頂点 P{0} と P{1} が一致しています（長さ0の {2}）',
    'CDL line {}: number {} before any record word': 'CDL {0} 行目：レコード名より前に数値 {1} があります',
    'fixture clearance must be a finite number >= 0 mm, got {}': '治具との逃げ量は0 mm以上の有限の数にしてください（指定：{0}）',
    "{}: move {} goes {} mm below the stock's bottom (Z {}) at ({}, {}): into the fixture or the table":
        '{0}：移動 {1} が ({4}, {5}) で素材の底面（Z {3}）より {2} mm 下まで入り、治具かテーブルを削ります',
    '{}: move {} cuts with the spindle at {} rpm': '{0}：移動 {1} は主軸 {2} rpm のまま切削します',
    '{}: {} = {} mm must be less than {} = {} mm: hits a diameter or more apart leave webs, and the part stays '
    'in the sheet':
        '{0}：{1} = {2} mm は {3} = {4} mm より小さくしてください：直径以上離れたヒットの間には桟が残り、製品が板から外れません',
    "{}: {}: the cut contour is {} x {} mm and reaches {} mm from the program's origin, beyond the {} mm the "
    "turret punch control addresses":
        '{0}：{1}：切断輪郭は {2} x {3} mm で、プログラム原点から {4} mm に達し、タレットパンチの制御装置が扱える {5} mm を超えています',
    '{}: {} = {} mm: {} takes {} hits, more than the {} one program may have; raise the pitch':
        '{0}：{1} = {2} mm：{3} には {4} ヒットが必要で、1 プログラムの上限 {5} を超えます。ピッチを大きくしてください',
    'the flat pattern of {}': '{0} の展開図',
    'edges P{}-P{} and P{}-P{} cross: give the corners in order round the quad':
        '辺 P{0}-P{1} と P{2}-P{3} が交差しています：頂点を四辺形の周に沿った順に指定してください',
    'piece {} of {} = {} mm': '{1} = {2} mm の {0} 番目のピース',
    '{}the part stays in the sheet (webs between the hits)':
        '{0}製品が板から外れません（ヒットの間に桟が残ります）',
    'not written: the punching simulation found {} fault(s): {}{}. Fix the job, or override knowingly '
    "(batch: --allow-findings; panel: Write Despite Findings in the export's file browser)":
        '書き出していません：パンチングのシミュレーションが {0} 件の不具合を見つけました：{1}{2}。'
        'ジョブを直すか、承知のうえで上書きしてください（バッチ：--allow-findings、パネル：書き出しのファイルブラウザーで「指摘があっても書き出す」）',
    '{}{}: beyond the {} mm the control addresses':
        '{0}{1}：制御装置が扱える {2} mm を超えています',
    'corner {} of the contour, G72 X{} Y{} (the line from it {} mm long), is beyond the {} mm the control '
    'addresses: the part does not fit the machine':
        '輪郭の頂点 {0}（G72 X{1} Y{2}、そこからの線の長さ {3} mm）が制御装置の扱える {4} mm を超えています：製品が機械に収まりません',
    'not written: the simulation found {} fault(s) in the {} program: {}{}. Fix the job, or override knowingly '
    '(batch: --allow-findings; panel: Simulate & Check > Write despite these findings)':
        '書き出していません：シミュレーションが {1} プログラムに {0} 件の不具合を見つけました：{2}{3}。'
        'ジョブを直すか、承知のうえで上書きしてください（バッチ：--allow-findings、パネル：シミュレーションと確認 > 指摘があっても書き出す）',
    ' (and {} more)': '（ほか {0} 件）',
    'Write despite these {} finding(s)': 'この {0} 件の指摘があっても書き出す',
    '{}: rapid move {} runs {} mm into material at ({}, {})': '{0}：早送り移動 {1} が ({3}, {4}) で材料に {2} mm 入り込みます',
    '{}: rapid move {} runs {} mm into material at {}': '{0}：早送り移動 {1} が {3} で材料に {2} mm 入り込みます',
    '{}: move {} cuts {} mm below the design at ({}, {}); {} mm^2 gouged in all':
        '{0}：移動 {1} が ({3}, {4}) で設計面より {2} mm 深く削ります。削り込みは合計 {5} mm^2',
    '{}: move {} cuts {} mm inside the design at ({}, {}, z {}); {} mm^2 gouged in all':
        '{0}：移動 {1} が ({3}, {4}, z {5}) で設計面より {2} mm 内側まで削ります。削り込みは合計 {6} mm^2',
    '{}: {} cannot plunge, but move {} feeds {} mm straight down into material at ({}, {})':
        '{0}：{1} は突っ込み加工できませんが、移動 {2} が ({4}, {5}) で材料へ {3} mm 真下に送ります',
    '{}: move {} goes {} the {} travel limit {} (reaches {}; {} move(s))':
        '{0}：移動 {1} が {3} のストローク制限 {4} を越えます（{2}、到達 {5}、{6} 移動）',
    '{}the part stays in the sheet: hits further apart than the punch leave webs (lower the pitch below the {} mm punch)':
        '{0}部品がシートから外れません：パンチ径より広い間隔の打ち抜きでつなぎが残ります（ピッチを {1} mm のパンチ径より小さくしてください）',
    '{}line {}: a hit bites {} mm into the part at ({}, {})': '{0}{1} 行目：打ち抜きが ({3}, {4}) で部品に {2} mm 食い込みます',
    '{}: {} cannot plunge, but move {} feeds {} mm straight in into material at {}':
        '{0}：{1} は突っ込み加工できませんが、移動 {2} が {4} で材料へ {3} mm まっすぐ送り込みます',
    # batch commands (operators/<workflow>.py) and the post registry
    '{} is not {} (allowed: {})': '{0} は{1}ではありません（指定できる範囲：{2}）',
    '{} is outside the allowed range {}': '{0} は指定できる範囲 {1} の外です',
    '{}: {} is not a value': '{0}：{1} は値ではありません',
    '{} {}: the setting would hold {} instead; give a value the setting allows':
        '{0} {1}：設定には代わりに {2} が入ってしまいます。設定が受け付ける値を指定してください',
    '--corners: every coordinate must be a finite number of mm, got {}': '--corners：座標はすべて有限の数 (mm) にしてください（指定：{0}）',
    '{}: no such .blend file': '{0}：.blend ファイルがありません',
    '{}: not a .blend file Blender can open ({})': '{0}：Blender で開ける .blend ファイルではありません（{1}）',
    '--stock {}: not numbers': '--stock {0}：数値ではありません',
    '--stock {}: give box:x0,y0,z0,x1,y1,z1 or cylinder:R,H': '--stock {0}：box:x0,y0,z0,x1,y1,z1 か cylinder:R,H で指定してください',
    'no such NC file: {}': 'NC ファイルがありません：{0}',
    '--corners: not numbers: {}': '--corners：数値ではありません：{0}',
    '--corners needs four "x,y,z" corners separated by ";", got {}':
        '--corners には ";" で区切った "x,y,z" の頂点が4つ必要です（指定：{0}）',
    'no such CDL file: {}': 'CDL ファイルがありません：{0}',
    'the {} post writes textured engravings only; pick another post':
        '{0} ポストプロセッサは刀跡テクスチャ付きの彫刻専用です。別のポストプロセッサを選んでください',
    '--order: instance ids separated by commas, got {}': '--order：インスタンス番号をカンマ区切りで指定してください（指定：{0}）',
    '--order: #{} is not a workingstep of {} ({})': '--order：#{0} は {1} のワーキングステップではありません（{2}）',
    'no such ISO 14649 file: {}': 'ISO 14649 ファイルがありません：{0}',
    '{} {}: no such file': '{0} {1}：ファイルがありません',
    # toolpath/operations/engrave/surface_engrave.py, operators/engrave.py: engraving on a curved plate
    'surface {}: {}': '曲面 {0}：{1}',
    'surface {}: vertices must be an (n, 3) array of numbers (mm)': '曲面 {0}：頂点は数値 (mm) の (n, 3) 配列にしてください',
    'surface {} does not cover the plate: nothing of it lies over or under X{} Y{}; it must be a mesh spanning the whole plate outline':
        '曲面 {0} が板材を覆っていません：X{1} Y{2} の上にも下にも面がありません。板材の輪郭全体にわたるメッシュにしてください',
    'surface {} does not cover the plate and the letters': '曲面 {0} が板材と文字を覆っていません',
    'surface {} has a hole under the {} near X{} Y{}: it must cover the whole plate':
        '曲面 {0} には {1} の下、X{2} Y{3} 付近に穴があります。板材全体を覆うようにしてください',
    '{}: arcs cannot follow a surface': '{0}：円弧は曲面に沿わせられません',
    '{} point(s) of the toolpaths were lifted to keep the tools off the letters (first near X{} Y{})':
        'ツールパスの {0} 点を文字に工具が当たらないよう持ち上げました（最初は X{1} Y{2} 付近）',
    'surface {} rises to Z {}: with the {} mm approach gap that reaches the clearance plane Z {}; lower the surface (the work zero) or raise the clearance plane':
        '曲面 {0} は Z {1} まで高くなり、{2} mm のアプローチの隙間を足すとクリアランス高さ Z {3} に届きます。曲面（ワーク原点）を下げるかクリアランス高さを上げてください',
    'on surface {} the deepest cut reaches Z {}, through the {} mm plate (its bottom is Z {}); make the cuts shallower or the plate thicker':
        '曲面 {0} 上の最も深い切込みが Z {1} に達し、厚さ {2} mm の板材（底面 Z {3}）を貫通します。切込みを浅くするか板材を厚くしてください',
    "plate surface {} is not a mesh: pick a mesh object whose top is the plate's top":
        '板材の曲面 {0} はメッシュではありません：上面が板材の上面になるメッシュオブジェクトを選んでください',
    'plate surface {} has no faces': '板材の曲面 {0} に面がありません',
    '--surface {}: no such file, nor a built-in surface ({})': '--surface {0}：ファイルがなく、組み込みの曲面（{1}）でもありません',
    'operation {}: texture marks need a texture and one (flag, fraction) pair per move':
        '工程 {0}：テクスチャの印にはテクスチャと、移動ごとに1組の（開始印, 割合）が必要です',
    'operation {}: links must mark feed moves, one flag per move':
        '工程 {0}：リンクの印は送り移動にだけ、移動ごとに1つ付けてください',
    # operators/limits.py: a panel or batch number outside its range
    '{}: {} = {} is outside the allowed range {}': '{0}：{1} = {2} は指定できる範囲 {3} の外です',
    # toolpath/engines/dropcutter.py, toolpath/operations/carve/carve.py, operators/carve.py
    'stock allowance must be a number >= 0 mm, got {}': '取り代は 0 mm 以上の数値にしてください（指定：{0}）',
    'a {} cannot leave a stock allowance (use a ball, flat or bull nose)':
        '{0} では取り代を残せません（ボール・フラット・ブルノーズを使ってください）',
    'vertices must be an (n, 3) array of mm, got shape {}': '頂点は (n, 3) の mm の配列にしてください（形：{0}）',
    'faces must be an (m, 3) array of vertex indices, got shape {}': '面は (m, 3) の頂点番号の配列にしてください（形：{0}）',
    'a face refers to vertex {}, but there are {}': '面が頂点 {0} を参照していますが、頂点は {1} 個です',
    'spacing and tolerance must be > 0 mm, got {}, {}': '間隔と許容値は 0 mm より大きくしてください（指定：{0}、{1}）',
    '{} must be a number >= 0, got {}': '{0} は 0 以上の数値にしてください（指定：{1}）',
    '{} must be greater than 0': '{0} は 0 より大きくしてください',
    'finishing needs a ball end mill (the scallop rule is a ball\'s), got a {}':
        '仕上げにはボールエンドミルが必要です（カスプ高さの式はボールのものです）。指定は {0} です',
    'roughing needs a flat, ball or bull nose end mill, got a {}':
        '荒加工にはフラット・ボール・ブルノーズのエンドミルが必要です。指定は {0} です',
    'scallop {} mm must be smaller than the ball\'s radius {} mm': 'カスプ高さ {0} mm はボールの半径 {1} mm より小さくしてください',
    'roughing stepover {} mm is wider than the {} mm tool': '荒加工のピックフィード {0} mm が工具径 {1} mm より広くなっています',
    'max slope must be 0..90 degrees, got {}': '最大傾斜は 0～90 度にしてください（指定：{0}）',
    'safe Z {} mm must be at least the clearance {} mm': '安全高さ Z {0} mm はクリアランス {1} mm 以上にしてください',
    'the design mesh needs (n, 3) vertices, got shape {}': '設計形状のメッシュには (n, 3) の頂点が必要です（形：{0}）',
    'the design mesh is flat in X or Y ({} x {} mm): nothing to carve':
        '設計形状のメッシュが X か Y 方向に平らです（{0} x {1} mm）：加工するものがありません',
    'stock top {} mm is below the design\'s highest point {} mm': '素材の上面 {0} mm が設計形状の最も高い点 {1} mm より下です',
    'faces slope up to {} degrees across the finishing raster; the stepover allows for {} degrees, so the scallop is higher there':
        '仕上げの走査に直交する方向で面の傾斜が最大 {0} 度あります。ピックフィードは {1} 度までを見込んでいるので、そこではカスプが高くなります',
    'design {} has no faces': '設計形状 {0} に面がありません',
    'Carving planned: {} moves, stepover {} mm, about {} min': '曲面加工を計画しました：{0} 移動、ピックフィード {1} mm、約 {2} 分',
    'faces in the steep regions slope up to {} degrees across the cleanup raster too; its stepover allows for {} '
    'degrees, so the scallop is higher there':
        '急斜面の追加仕上げの走査に直交する方向でも面の傾斜が最大 {0} 度あります。そのピックフィードは {1} 度までを'
        '見込んでいるので、そこではカスプが高くなります',
    '{} mm2 of walls are steeper than {} degrees across both rasters (or vertical) and Wall Pass is off: no raster '
    'finishes them':
        '{0} mm2 の壁が両方の走査に直交する方向で {1} 度より急（または垂直）で、壁の等高線仕上げがオフです。'
        'どの走査でも仕上がりません',
    'the wall pass would need {} waterline levels {} mm apart (walls as shallow as {} degrees, steeper than Max '
    'Slope {}): raise Max Slope or turn Wall Pass off':
        '壁の等高線仕上げに {1} mm 間隔で {0} 段の等高線が必要です（最も緩い壁は {2} 度で、最大傾斜 {3} より急です）。'
        '最大傾斜を上げるか、壁の等高線仕上げをオフにしてください',
    'Wall pass: waterlines {} mm apart in Z on {} mm2 of walls, {} levels, scallop {} mm on the least steep wall':
        '壁の等高線仕上げ：{1} mm2 の壁を Z {0} mm ごとの等高線 {2} 段で削りました。最も緩い壁のカスプ {3} mm',
    'Steep cleanup: {} mm2 of faces steeper than {} degrees across the raster, cut again across it at a {} mm '
    'stepover':
        '急斜面の追加仕上げ：走査に直交する方向で {1} 度より急な面 {0} mm2 を、それに直交する走査でピックフィード '
        '{2} mm でもう一度削りました',
    '{} {}: not a readable mesh ({})': '{0} {1}：読み込めるメッシュではありません（{2}）',
    '{} {}: the mesh has no faces': '{0} {1}：メッシュに面がありません',
    '{} {}: the mesh has a non-finite vertex coordinate (NaN or infinity)':
        '{0} {1}：メッシュに有限でない頂点座標（NaN または無限大）があります',
    '{} {}: a face has a vertex index outside 0..{}': '{0} {1}：面の頂点番号が 0..{2} の外にあります',
    'no workflow {}; the table has {}': 'ワークフロー {0} はありません。あるのは {1} です',
    'post class {} needs {}': 'ポストプロセッサのクラス {0} には {1} が必要です',
    'post {} ({}, {}) is already registered by {}.{}': 'ポストプロセッサ {0}（{1}、{2}）は {3}.{4} が登録済みです',
    # toolpath/stepnc: warnings and notes on files written by other tools
    "workingstep #{} '{}' skipped: {}": "ワーキングステップ #{0} '{1}' を飛ばしました：{2}",
    "the {} post would write a line of {} characters, more than the {} the control reads: {}...":
        "{0} ポストプロセッサは {1} 文字の行を書くことになり、制御装置が読める {2} 文字を超えます：{3}...",
    "a helix of pitch {} mm down {} mm makes more than {} turns":
        "ピッチ {0} mm のヘリカルで {1} mm 下りると {2} 回転を超えます",
    "tools without a usable number in their identifier, numbered in order of first use: {}":
        "識別子に使える番号のない工具は、最初に使う順に番号を付けました：{0}",
    "{} names T{}, not a tool number every control takes (1..{})":
        "{0} は T{1} を指定していますが、どの制御装置でも使える工具番号（1〜{2}）ではありません",
    "{} and #{} '{}' both claim T{} but are different tools (identifier, body or dimensions): #{} keeps T{}":
        "{0} と #{1} '{2}' はどちらも T{3} を名乗っていますが、別の工具です（識別子、本体または寸法が違います）："
        "T{5} は #{4} のものです",
    "ROUND_HOLE #{} '{}' has a {} but workingstep #{} '{}' drills it with a {} degree point: the tip stops at the "
    "depth (Z {}) and leaves a cone {} mm high (the full diameter reaches Z {}); no workingstep cuts the bottom "
    "flat: add a flat end mill or counterbore workingstep, or finish it by hand":
        "ROUND_HOLE #{0} '{1}' は {2} ですが、ワーキングステップ #{3} '{4}' は先端角 {5} 度のドリルで加工します："
        "先端は深さ（Z {6}）で止まり、高さ {7} mm の円すいが残ります（全径が届くのは Z {8} まで）。底を平らに削る"
        "ワーキングステップがありません：フラットエンドミルかカウンタボアのワーキングステップを加えるか、手で仕上げてください",
    'no workingstep can be machined: {}': '加工できるワーキングステップがありません：{0}',
    "{}: its profile #{} repeats the pocket's placement #{} ({}); read as one placement (the pocket at {}), not "
    "composed (which would put it at {}); the file gives no stock BLOCK to check against":
        "{0}：輪郭 #{1} がポケットの配置 #{2}（{3}）を繰り返しています。合成せず1つの配置として読みました"
        "（ポケットは {4}。合成すると {5}）。ファイルに照合できる素材 BLOCK がありません",
    "{}: composed with its profile's placement #{} the pocket would reach {} mm beyond the stock BLOCK #{}; the "
    "profile's placement is read as absolute (the generator wrote the pocket's placement twice): the pocket is cut "
    "at {} on the stock":
        "{0}：輪郭の配置 #{1} と合成するとポケットが素材 BLOCK #{3} から {2} mm はみ出します。輪郭の配置を絶対座標と"
        "して読みました（生成元がポケットの配置を二重に書いています）：ポケットは素材上の {4} に加工します",
    "{}: reaches {} mm beyond the stock BLOCK #{} (and {} mm with its profile's placement read as absolute); cut as "
    "written, check the file":
        "{0}：素材 BLOCK #{2} から {1} mm はみ出します（輪郭の配置を絶対座標として読んでも {3} mm）。"
        "書かれたとおりに加工します。ファイルを確認してください",
    "#{} MILLING_TECHNOLOGY: spindle {} rev/s would be S{}; the file gives rpm where ISO 14649 says rev/s (as "
    "2012-era generators wrote it): S{} written":
        "#{0} MILLING_TECHNOLOGY：主軸 {1} rev/s は S{2} になります。ISO 14649 が rev/s とするところにファイルは "
        "rpm を書いています（2012年ごろの生成元の書き方）：S{3} と書き出します",
    '{}: S{} is beyond any spindle (more than {} rpm)': '{0}：S{1} はどの主軸の能力も超えています（{2} rpm 超）',
    "{}: S{} runs the {} mm tool's rim at {} m/min (more than {} m/min)":
        "{0}：S{1} では {2} mm の工具の外周速度が {3} m/min になります（{4} m/min 超）",
    '{}: feed {} mm/min is more than {} mm/min (was the feedrate written in another unit than m/s?)':
        '{0}：送り {1} mm/min は {2} mm/min を超えています（feedrate が m/s 以外の単位で書かれていませんか？）',
    '{}: {} mm per revolution is too much for the {} mm tool (at most {})':
        '{0}：1回転あたり {1} mm は {2} mm の工具には大きすぎます（上限 {3}）',
    '{}: {} mm per tooth is too much for the {} mm tool with {} teeth (at most {})':
        '{0}：1刃あたり {1} mm は刃数 {3} の {2} mm の工具には大きすぎます（上限 {4}）',
    '{}: {} mm per tooth is below {} mm: the tool rubs': '{0}：1刃あたり {1} mm は {2} mm 未満です：工具がこすれるだけです',
    "#{} LINEAR_PATH: the slot's distance must be positive, found {}":
        "#{0} LINEAR_PATH：溝の長さ（distance）は正の値にしてください（値 {1}）",
    '#{} SQUARE_U_PROFILE: width must be positive, found {}': '#{0} SQUARE_U_PROFILE：幅は正の値にしてください（値 {1}）',
    "the flat end of slot #{} keeps the tool's radius R{} in its corners":
        "溝 #{0} の平らな端の隅には工具の半径 R{1} が残ります",
    # toolpath/operations/stepnc/ap238*.py: the AP238 integrated form
    '#{} {}: {} must refer to an instance, found {}': '#{0} {1}：{2} はインスタンスを参照してください（値 {3}）',
    '#{} {}: the value must be a number, found {}': '#{0} {1}：値は数値にしてください（値 {2}）',
    'an AP238 file needs exactly one MACHINING_PROJECT, this one has {}':
        'AP238 ファイルには MACHINING_PROJECT がちょうど1つ必要ですが、このファイルには {0} 個あります',
    "#{} MACHINING_PROJECT: no main MACHINING_WORKPLAN (a PRODUCT_DEFINITION_PROCESS 'machining' of its "
    "PRODUCT_DEFINITION #{})":
        "#{0} MACHINING_PROJECT：メインの MACHINING_WORKPLAN がありません（PRODUCT_DEFINITION #{1} の "
        "PRODUCT_DEFINITION_PROCESS 'machining'）",
    '#{} {}: no PRODUCT_DEFINITION_FORMATION and PRODUCT_DEFINITION refer to it':
        '#{0} {1}：これを参照する PRODUCT_DEFINITION_FORMATION と PRODUCT_DEFINITION がありません',
    '#{} BLOCK_SHAPE_REPRESENTATION: no {} item': '#{0} BLOCK_SHAPE_REPRESENTATION：{1} の項目がありません',
    '#{} MACHINING_WORKPLAN contains itself (through #{})': '#{0} MACHINING_WORKPLAN が（#{1} を通じて）自身を含んでいます',
    "#{} MACHINING_WORKINGSTEP '{}': no 'security plane' ACTION_PROPERTY with a PLANE":
        "#{0} MACHINING_WORKINGSTEP '{1}'：PLANE を持つ ACTION_PROPERTY 'security plane'（安全平面）がありません",
    "#{} MACHINING_WORKINGSTEP '{}': needs one MACHINING_OPERATION_RELATIONSHIP, found {}":
        "#{0} MACHINING_WORKINGSTEP '{1}'：MACHINING_OPERATION_RELATIONSHIP が1つ必要ですが {2} 個あります",
    "#{} MACHINING_WORKINGSTEP '{}': no feature (a MACHINING_FEATURE_RELATIONSHIP to a MACHINING_FEATURE_PROCESS "
    "with a PROPERTY_PROCESS)":
        "#{0} MACHINING_WORKINGSTEP '{1}'：フィーチャがありません（PROPERTY_PROCESS を持つ MACHINING_FEATURE_PROCESS "
        "への MACHINING_FEATURE_RELATIONSHIP）",
    "#{} {} '{}': no {} (a feature component through a SHAPE_ASPECT '{} occurrence')":
        "#{0} {1} '{2}'：{3} がありません（SHAPE_ASPECT '{4} occurrence' を通じたフィーチャ要素）",
    '#{} {}: no length item in its representation': '#{0} {1}：表現に長さの項目がありません',
    "#{} {}: no '{}' item in its representation": "#{0} {1}：表現に '{2}' の項目がありません",
    "#{} PATH_FEATURE_COMPONENT: a linear path needs a DIRECTION and a 'distance'":
        "#{0} PATH_FEATURE_COMPONENT：直線の経路には DIRECTION と 'distance' が必要です",
    "#{} PATH_FEATURE_COMPONENT: a circular path needs a 'radius'":
        "#{0} PATH_FEATURE_COMPONENT：円弧の経路には 'radius' が必要です",
    "#{} PATH_FEATURE_COMPONENT: a partial circular path needs a 'sweep angle'":
        "#{0} PATH_FEATURE_COMPONENT：部分円弧の経路には 'sweep angle' が必要です",
    "#{} PATH_FEATURE_COMPONENT: a complex path needs a curve ('sweep path')":
        "#{0} PATH_FEATURE_COMPONENT：一般の経路には曲線（'sweep path'）が必要です",
    "#{} RECTANGULAR_CLOSED_PROFILE: needs 'width' and 'length' items":
        "#{0} RECTANGULAR_CLOSED_PROFILE：'width' と 'length' の項目が必要です",
    '#{} CLOSED_PATH_PROFILE: no curve in its PATH_SHAPE_REPRESENTATION':
        '#{0} CLOSED_PATH_PROFILE：PATH_SHAPE_REPRESENTATION に曲線がありません',
    "#{} {} '{}': no PRODUCT_DEFINITION_SHAPE refers to it": "#{0} {1} '{2}'：これを参照する PRODUCT_DEFINITION_SHAPE がありません",
    "#{} {} '{}': no placement (an AXIS2_PLACEMENT_3D 'orientation' in the SHAPE_REPRESENTATION_WITH_PARAMETERS of "
    "its PRODUCT_DEFINITION_SHAPE)":
        "#{0} {1} '{2}'：配置がありません（PRODUCT_DEFINITION_SHAPE の SHAPE_REPRESENTATION_WITH_PARAMETERS にある "
        "AXIS2_PLACEMENT_3D 'orientation'）",
    "#{} {} '{}': no depth (a PLANE in its SHAPE_REPRESENTATION 'maximum feature limit')":
        "#{0} {1} '{2}'：深さがありません（SHAPE_REPRESENTATION 'maximum feature limit' の PLANE）",
    "#{} POCKET '{}': no bottom condition (a POCKET_BOTTOM through a 'bottom condition occurrence')":
        "#{0} POCKET '{1}'：底の条件がありません（'bottom condition occurrence' を通じた POCKET_BOTTOM）",
    "#{} MACHINING_TOOL_BODY_REPRESENTATION '{}': no 'effective cutting diameter' item":
        "#{0} MACHINING_TOOL_BODY_REPRESENTATION '{1}'：'effective cutting diameter'（有効切削径）の項目がありません",
    "#{} {} '{}': needs one MACHINING_TOOL whose usage lists it, found {}":
        "#{0} {1} '{2}'：usage にこれを挙げる MACHINING_TOOL が1つ必要ですが {3} 個あります",
    "#{} {} '{}': no MACHINING_TECHNOLOGY_RELATIONSHIP": "#{0} {1} '{2}'：MACHINING_TECHNOLOGY_RELATIONSHIP がありません",
    "#{} MACHINING_TOOL '{}': no 'tool body' RESOURCE_PROPERTY with a MACHINING_TOOL_BODY_REPRESENTATION":
        "#{0} MACHINING_TOOL '{1}'：MACHINING_TOOL_BODY_REPRESENTATION を持つ RESOURCE_PROPERTY 'tool body' がありません",
    '#{} {}: attribute number {} is missing; the instance has {} attributes':
        '#{0} {1}：{2} 番目の属性がありません（このインスタンスの属性は {3} 個）',
    'the AP238 data does not follow the mapping of ISO 10303-238 near #{} ({}: {})':
        'AP238 のデータが ISO 10303-238 の対応付けに従っていません（#{0} 付近、{1}：{2}）',
    # toolpath/operations/stepnc/freeform.py and geometry.py: explicit toolpaths and rapid movements
    '#{} COMPOSITE_CURVE: a segment starts away from the end of the one before it':
        '#{0} COMPOSITE_CURVE：セグメントが前のセグメントの終点から離れて始まっています',
    '#{} HELIX: the pitch is zero': '#{0} HELIX：ピッチが0です',
    '#{} TRIMMED_CURVE: {} turns about #{}, more than {}': '#{0} TRIMMED_CURVE：#{2} の周りを {1} 回転します（上限 {3}）',
    '#{} B_SPLINE_CURVE_WITH_KNOTS: its control polygon is {} mm long, more than {} mm':
        '#{0} B_SPLINE_CURVE_WITH_KNOTS：制御多角形の長さが {1} mm あり、{2} mm を超えています',
    '#{} B_SPLINE_CURVE_WITH_KNOTS: degree, knot_multiplicities and knots must be a degree of 1 to 25 and two '
    'lists of the same length (multiplicities 1 to degree + 1)':
        '#{0} B_SPLINE_CURVE_WITH_KNOTS：degree は1〜25、knot_multiplicities と knots は同じ長さのリスト'
        '（多重度は1〜次数+1）にしてください',
    '#{} B_SPLINE_CURVE_WITH_KNOTS: {} control points of degree {} need {} non-decreasing knots, found {}':
        '#{0} B_SPLINE_CURVE_WITH_KNOTS：次数 {2} の制御点 {1} 個には単調非減少のノットが {3} 個必要ですが {4} 個です',
    '#{} TRIMMED_CURVE: its points lie {} and {} mm from the axis of #{}, whose radius is {} mm':
        '#{0} TRIMMED_CURVE：点が #{3} の軸から {1} mm と {2} mm の位置にありますが、その半径は {4} mm です',
    '#{} TRIMMED_CURVE: sense_agreement .T. contradicts the pitch of the HELIX #{} (its second point is below its '
    'first)':
        '#{0} TRIMMED_CURVE：sense_agreement .T. が HELIX #{1} のピッチと矛盾します（2点目が1点目より下にあります）',
    '#{} TRIMMED_CURVE: sense_agreement .F. contradicts the pitch of the HELIX #{} (its second point is above its '
    'first)':
        '#{0} TRIMMED_CURVE：sense_agreement .F. が HELIX #{1} のピッチと矛盾します（2点目が1点目より上にあります）',
    '#{} TRIMMED_CURVE: its points are not on the HELIX #{} (angle and height disagree)':
        '#{0} TRIMMED_CURVE：点が HELIX #{1} 上にありません（角度と高さが合いません）',
    "rapid movement #{} '{}' skipped: {}": "早送り移動 #{0} '{1}' を飛ばしました：{2}",
    "rapid movement #{} '{}' skipped: no workingstep before it in its workplan, so no tool to move":
        "早送り移動 #{0} '{1}' を飛ばしました：ワークプランで前にワーキングステップがなく、動かす工具がありません",
    "rapid movement #{} '{}' after workingstep #{} left out: the path planned for the workingstep makes its own "
    "links":
        "ワーキングステップ #{2} の後の早送り移動 #{0} '{1}' は使いません：そのワーキングステップ用に計画した経路が"
        "自前でつなぎます",
    'trajectory #{} starts {} mm from the end of the one before it: joined by a straight feed move':
        '軌跡 #{0} は前の軌跡の終点から {1} mm 離れて始まります：直線の切削送りでつなぎました',
    "trajectory #{} asks for S{}; the operation's S{} is written (one spindle speed per operation)":
        "軌跡 #{0} は S{1} を指定していますが、オペレーションの S{2} を書き出します（オペレーションごとに主軸回転数は1つ）",
    '{} #{} is not supported': '{0} #{1} は対応していません',
    '{} #{} is not supported ({})': '{0} #{1} は対応していません（{2}）',
    "{}: no contour pass on planar face #{}, its strokes run out past the face's edges":
        "{0}：平面 #{1} には輪郭パスを入れません。往復の送りが面の縁の外まで抜けます",
    '#{} GENERAL_PATH: the swept_path has no length': '#{0} GENERAL_PATH：swept_path に長さがありません',
    'the stock bottom is unknown (no workpiece BLOCK and no through feature): feature depths are not checked '
    'against the stock':
        '素材の底が分かりません（ワークの BLOCK も貫通フィーチャもありません）：フィーチャの深さを素材と照合していません',
    "{}: the holes {} start on its floor (Z {}) and lie in it only with its profile's placement #{} read as "
    "absolute, not composed with the pocket's #{}; read so (the generator wrote the pocket's placement twice): the "
    "pocket is cut at {}":
        "{0}：穴 {1} はポケットの底（Z {2}）から始まり、輪郭の配置 #{3} をポケットの配置 #{4} と合成せず絶対座標として"
        "読んだときだけポケットの中にあります。そのように読みました（生成元がポケットの配置を二重に書いています）："
        "ポケットは {5} に加工します",
    '#{} {}: radius must be positive and sweep_angle within 0 to 360 degrees, found radius {} and sweep {}':
        '#{0} {1}：半径は正、sweep_angle は0〜360度にしてください（半径 {2}、角度 {3}）',
    'line {}: {} is not a word (a letter and a number) in {}':
        '{0}行目：{1}：ワード（英字と数値）ではありません：{2}',
    'line {}: {} is not followed by a number in {}': '{0}行目：{1} の後に数値がありません：{2}',
    'line {}: {} is not followed by a number (found {}) in {}':
        '{0}行目：{1} の後に数値がありません（{2} があります）：{3}',
    'line {}: {}{} is not a number G-code can have in {}':
        '{0}行目：{1}{2} はGコードで使える数値ではありません：{3}',
    'line {}: {}{}E...: exponents are not allowed in G-code numbers, in {}':
        '{0}行目：{1}{2}E...：Gコードの数値に指数表記は使えません：{3}',
    'line {}: {}{} is out of range in {}':
        '{0}行目：{1}{2} は範囲外です：{3}',
    'line {}: unbalanced or nested parenthesis in {}':
        '{0}行目：括弧の対応が取れていないか入れ子になっています：{1}',
    'line {}: the arc has no radius (its centre is its start or end point) in {}':
        '{0}行目：円弧に半径がありません（中心が始点または終点です）：{1}',
    "line {}: the arc's end lies {} mm off its circle (radius {} mm at the start, {} mm at the end; LinuxCNC allows {} mm) in {}":
        '{0}行目：円弧の終点が円から {1} mm ずれています（始点の半径 {2} mm、終点の半径 {3} mm。LinuxCNC の許容は {4} mm）：{5}',
    'line {}: N{} is not a sequence number in {}':
        '{0}行目：N{1} はシーケンス番号ではありません：{2}',
    'line {}: {} is given twice in {}':
        '{0}行目：{1} が2回指定されています：{2}',
    'line {}: {} are both motions in {}':
        '{0}行目：{1}：どちらも移動指令です：{2}',
    'line {}: {} and {} are in one modal group, so one block cannot have both: {}':
        '{0}行目：{1} と {2} は同じモーダルグループなので、1つのブロックに両方は書けません：{3}',
    # toolpath/operations/engrave/engrave.py, toolpath/engines/ramp.py: the band's step-downs and ramps
    "band step down {} mm is more than the {} mm finishing tool's diameter: a small flat end mill takes at most 1 x its diameter in depth per pass":
        'バンドの切込み {0} mm が仕上げ工具の直径 {1} mm を超えています：小径のフラットエンドミルの1回の切込みは直径の1倍までです',
    'band ramp angle must be more than 0 and at most {} degrees, got {}':
        'バンドのランプ角度は 0 より大きく {0} 度以下にしてください（{1} が指定されました）',
    'ramp angle must be more than 0 and at most {} degrees, got {}':
        'ランプ角度は 0 より大きく {0} 度以下にしてください（{1} が指定されました）',
    'step down must be a number > 0 mm, got {}':
        '切込みは 0 mm より大きい数にしてください（{0} が指定されました）',
    'depth {} must lie below the top Z {}':
        '深さ {0} は上面 Z {1} より下にしてください',
    'line {}: {}{} lies beyond the {} mm any machine reaches: {}':
        '{0}行目：{1}{2} はどの機械も届かない {3} mm の外です：{4}',
    'line {}: F{} is a negative feed, which no control takes: {}':
        '{0}行目：F{1} は負の送りで、どの制御装置も受け付けません：{2}',
    'line {}: G4 P{} is a negative dwell: {}':
        '{0}行目：G4 P{1} は負のドウェルです：{2}',
    'line {}: a G{} move with no F word before it (a control refuses a cutting move without a feed): {}':
        '{0}行目：G{1} の移動の前に F がありません（送りのない切削移動は制御装置が受け付けません）：{2}',
    'line {}: a G{} move with F0 in effect since line {} (a control refuses a cutting move without a feed): {}':
        '{0}行目：{2}行目から F0 のままの G{1} の移動です（送りのない切削移動は制御装置が受け付けません）：{3}',
    'line {}: S{} is not a spindle speed: {}':
        '{0}行目：S{1} は主軸回転数ではありません：{2}',
    "line {}: a block delete '/' is not followed (whether the control skips the line depends on its Block Delete switch): {}":
        '{0}行目：ブロックデリート「/」には対応していません（その行を飛ばすかは制御装置のブロックデリートスイッチ次第です）：{1}',
    'line {}: {} {}: {}':
        '{0}行目：{1} {2}：{3}',
    'line {}: {} is not a code this reader knows: {}':
        '{0}行目：{1}：この読み込みで扱えないコードです：{2}',
    'line {}: R-format arcs are not supported; use I and J: {}':
        '{0}行目：R指定の円弧には対応していません。I と J を使ってください：{1}',
    'line {}: the {} word is not supported here: {}':
        '{0}行目：{1} ワードはここでは使えません：{2}',
    'line {}: G28 is followed only as G91 G28 with zero words (home is not known to the reader): {}':
        '{0}行目：G28 はゼロのワードを伴う G91 G28 だけに対応します（原点位置は分かりません）：{1}',
    'line {}: I or J without an arc move in {}':
        '{0}行目：円弧移動でないのに I または J があります：{1}',
    'line {}: a move before any G0/G1/G2/G3: {}':
        '{0}行目：G0/G1/G2/G3 より前に移動があります：{1}',
    'line {}: an incremental (G91) move before any absolute position of {}: {}':
        '{0}行目：{1} の絶対位置が分かる前にインクリメンタル（G91）移動があります：{2}',
    'line {}: an arc needs I and J: {}':
        '{0}行目：円弧には I と J が必要です：{1}',
    "line {}: an arc before the tool's XY position is known: {}":
        '{0}行目：工具のXY位置が分かる前に円弧があります：{1}',
    '--tool {}: sizes must be finite numbers > 0, the corner radius at most half the diameter':
        '--tool {0}：寸法は 0 より大きい有限の数で、コーナー半径は直径の半分以下にしてください',
    'cell {} mm is too coarse for a stock {} mm across (fewer than {} cells): give a cell from {} to {} mm':
        'セル {0} mm は幅 {1} mm の素材には粗すぎます（{2} セル未満）：{3}～{4} mm のセルを指定してください',
    'design {}: vertices and faces must be numeric arrays':
        '設計形状 {0}：頂点と面は数値の配列にしてください',
    'design {}: the mesh has no faces (an empty or unreadable mesh file)':
        '設計形状 {0}：メッシュに面がありません（空または読み込めないメッシュファイル）',
    'design {}: needs (n, 3) vertices and (m, 3) triangles, got {} and {}':
        '設計形状 {0}：(n, 3) の頂点と (m, 3) の三角形が必要ですが、{1} と {2} でした',
    'design {}: face indices must be integers in 0..{}':
        '設計形状 {0}：面の頂点番号は 0..{1} の整数にしてください',
    'design {}: the mesh has NaN or infinite vertex coordinates':
        '設計形状 {0}：メッシュの頂点座標に NaN または無限大があります',
    "design {}: the mesh is not a closed solid: {}; close it (e.g. Blender's Fill Holes, or 3D-Print Toolbox > Make Manifold)":
        '設計形状 {0}：メッシュが閉じた立体ではありません：{1}。閉じてください（例：Blender の「穴を埋める」や 3D-Print Toolbox の「Make Manifold」）',
    'design {}: the faces are wound inconsistently (some normals are flipped): recalculate normals':
        '設計形状 {0}：面の向きがそろっていません（一部の法線が反転しています）：法線を再計算してください',
    'design {}: the mesh encloses no volume':
        '設計形状 {0}：メッシュが体積を囲んでいません',
    'design {}: the part ({}, {}, {})..({}, {}, {}) does not overlap the stock: are both in the same coordinates?':
        '設計形状 {0}：部品 ({1}, {2}, {3})..({4}, {5}, {6}) が素材と重なりません：同じ座標系ですか？',
    'design {}: the part stands {} mm outside the stock (more than {} mm): it cannot be cut from this stock':
        '設計形状 {0}：部品が素材から {1} mm はみ出しています（{2} mm 超）：この素材からは削り出せません',
    'design {}: the mesh was inside out (its normals pointed inward); its faces were flipped':
        '設計形状 {0}：メッシュが裏返しでした（法線が内向き）。面を反転しました',
    'design {}: the mesh passes through itself ({} pair(s) of faces cross, the first faces {} and {} at ({}, {}, {}) mm), so its inside is ambiguous: join the pieces with a boolean union (Blender: Boolean modifier, or 3D-Print Toolbox > Intersections to find them)':
        '設計形状 {0}：メッシュが自己交差しています（交差する面の組 {1} 組、最初は面 {2} と {3}、位置 ({4}, {5}, {6}) mm）。内側が定まりません：ブーリアンの結合で一体にしてください（Blender：ブーリアンモディファイアー、交差の確認は 3D-Print Toolbox の Intersections）',
    'line {}: the pitch Q{} is below the {} mm a turret punch nibbles at (give Q from {} mm up): {}':
        '{0}行目：ピッチ Q{1} はタレットパンチのニブリングの下限 {2} mm を下回っています（Q は {3} mm 以上にしてください）：{4}',
    'line {}: the program has more than {} hits by this line (at most {} are simulated): check the pitches Q':
        '{0}行目：この行までにヒット数が {1} を超えています（シミュレーションできるのは {2} まで）：ピッチ Q を確認してください',
    '{} must be from {} to {}, got {}':
        '{0} は {1}～{2} にしてください（指定値 {3}）',
    '{} {} is a file, not a folder':
        '{0} {1} はファイルです（フォルダーを指定してください）',
    '{} {} cannot be made: {} is a file':
        '{0} {1} を作れません：{2} はファイルです',
    '{} {} cannot be written':
        '{0} {1} に書き込めません',
    '{} {} cannot be made: {} cannot be written':
        '{0} {1} を作れません：{2} に書き込めません',
    'cannot write {}: nothing was written':
        '{0} を書き込めません：何も書き込まれませんでした',
    'cannot write {}: cannot make the folder {} ({})':
        '{0} を書き込めません：フォルダー {1} を作れません（{2}）',
    'cannot write {}: the text is not ASCII ({} at character {})':
        '{0} を書き込めません：テキストが ASCII ではありません（{2} 文字目の {1}）',
    'cannot write {}: {}':
        '{0} を書き込めません：{1}',
    '{} {} cannot be written: {}':
        '{0} {1} に書き込めません：{2}',
    'cannot write {}: a folder of that name is in the way':
        '{0} を書き込めません：同じ名前のフォルダーがあります',
    'cannot move the files into {}: {}':
        'ファイルを {0} に移せません：{1}',
    # toolpath/ir/arcfit.py
    'arc tolerance must lie in 0..1 mm, got {}':
        '円弧の許容差は 0～1 mm にしてください（指定値 {0}）',
    'an arc must replace at least 2 chords, got {}':
        '円弧は少なくとも 2 本の弦を置き換えます（指定値 {0}）',
    'arc end tolerance must be a positive length in mm, got {}':
        '円弧終点の許容差は正の長さ (mm) にしてください（指定値 {0}）',
    "the number format's least increment must lie in 0..0.1 mm, got {}":
        '数値書式の最小設定単位は 0～0.1 mm にしてください（指定値 {0}）',
    # toolpath/ir/machine.py
    'unknown machine {}: the presets are {}':
        '機械 {0} はありません。プリセットは {1} です',
    'machine profile {}: {} = {} {}':
        '機械プロファイル {0}：{1} = {2} {3}',
    # toolpath/simulate/ncread.py: the refused codes (REFUSED), each its own template so the reason is Japanese too
    'line {}: {} NURBS are not simulated: {}':
        '{0}行目：{1}：NURBS はシミュレーションしません：{2}',
    'line {}: {} cancels a coordinate rotation, which the reader does not follow: {}':
        '{0}行目：{1}：座標回転を取り消しますが、読み込みでは扱えません：{2}',
    'line {}: {} canned cycles are not simulated: {}':
        '{0}行目：{1}：固定サイクルはシミュレーションしません：{2}',
    'line {}: {} changes tool or offset tables, which the reader does not follow: {}':
        '{0}行目：{1}：工具・オフセット表を変更しますが、読み込みでは扱えません：{2}',
    'line {}: {} constant surface speed is not simulated: {}':
        '{0}行目：{1}：周速一定制御はシミュレーションしません：{2}',
    'line {}: {} cutter radius compensation is not simulated: {}':
        '{0}行目：{1}：工具径補正はシミュレーションしません：{2}',
    'line {}: {} feed per revolution is not simulated: {}':
        '{0}行目：{1}：回転当たり送りはシミュレーションしません：{2}',
    'line {}: {} macro calls are not simulated: {}':
        '{0}行目：{1}：マクロ呼び出しはシミュレーションしません：{2}',
    'line {}: {} moves in machine coordinates, which the reader does not know: {}':
        '{0}行目：{1}：機械座標で移動しますが、読み込みでは機械座標が分かりません：{2}',
    'line {}: {} probing moves are not simulated: {}':
        '{0}行目：{1}：プローブ移動はシミュレーションしません：{2}',
    'line {}: {} resets coordinate offsets, which the reader does not follow: {}':
        '{0}行目：{1}：座標オフセットをリセットしますが、読み込みでは扱えません：{2}',
    'line {}: {} restores coordinate offsets, which the reader does not follow: {}':
        '{0}行目：{1}：座標オフセットを復元しますが、読み込みでは扱えません：{2}',
    'line {}: {} returns to a reference point the reader does not know: {}':
        '{0}行目：{1}：読み込みでは分からない基準点へ戻ります：{2}',
    'line {}: {} rotates the coordinate system, which the reader does not follow: {}':
        '{0}行目：{1}：座標系を回転しますが、読み込みでは扱えません：{2}',
    'line {}: {} selects another plane; only the XY plane (G17) is read: {}':
        '{0}行目：{1}：別の平面を選びます。読めるのは XY 平面（G17）だけです：{2}',
    'line {}: {} sets a coordinate offset, which the reader does not follow: {}':
        '{0}行目：{1}：座標オフセットを設定しますが、読み込みでは扱えません：{2}',
    'line {}: {} sets a local coordinate offset, which the reader does not follow: {}':
        '{0}行目：{1}：ローカル座標オフセットを設定しますが、読み込みでは扱えません：{2}',
    'line {}: {} sets absolute arc centres, which the reader does not follow (use incremental I, J): {}':
        '{0}行目：{1}：円弧中心をアブソリュートにしますが、読み込みでは扱えません（インクリメンタルの I、J を使ってください）：{2}',
    'line {}: {} sets the reference point, which the reader does not know: {}':
        '{0}行目：{1}：基準点を設定しますが、読み込みでは分かりません：{2}',
    'line {}: {} splines are not simulated: {}':
        '{0}行目：{1}：スプラインはシミュレーションしません：{2}',
    'line {}: {} subprogram calls are not simulated: {}':
        '{0}行目：{1}：サブプログラム呼び出しはシミュレーションしません：{2}',
    'line {}: {} subprogram returns are not simulated: {}':
        '{0}行目：{1}：サブプログラムからの復帰はシミュレーションしません：{2}',
    'line {}: {} suspends coordinate offsets, which the reader does not follow: {}':
        '{0}行目：{1}：座標オフセットを一時停止しますが、読み込みでは扱えません：{2}',
    'line {}: {} tapping is not simulated: {}':
        '{0}行目：{1}：タッピングはシミュレーションしません：{2}',
    'line {}: {} threading is not simulated: {}':
        '{0}行目：{1}：ねじ切りはシミュレーションしません：{2}',
    # toolpath/pictures/picture.py, operators/convert.py, operators/__init__.py
    'picture size must be whole pixels, 16..8192, got {} x {}':
        '画像の大きさは 16〜8192 の整数ピクセルにしてください（指定値 {0} x {1}）',
    'the drawing area {} is too small': '描画領域 {0} が小さすぎます',
    'an image must be (height, width, 3), got {}': '画像は (高さ, 幅, 3) の配列にしてください（指定値 {0}）',
    'mesh {}: a face index is outside 0..{}': 'メッシュ {0}：面の頂点番号が 0〜{1} の範囲外です',
    'Kezuri: the simulation kernels were not compiled ahead ({}); the first Simulate compiles them':
        'Kezuri：シミュレーションのカーネルを前もってコンパイルできませんでした（{0}）。最初のシミュレーションでコンパイルします',
    # jobs and job files (issue 28)
    '{}: settings.{} is not a drilling setting; they are {}': '{0}：settings.{1} は穴あけの設定ではありません（設定は {2}）',
    '{}: settings.{} = {} is not a number': '{0}：settings.{1} = {2} は数値ではありません',
    '{}: settings.tool_number = {} is not a whole number': '{0}：settings.tool_number = {1} は整数ではありません',
    '{}: the drill: {}': '{0}：ドリル：{1}',
    '{}: the holes or the drill: {}': '{0}：穴またはドリル：{1}',
    '{}: drilling takes its holes as holes = [[x, y], ...], not objects':
        '{0}：穴あけの穴はオブジェクトではなく holes = [[x, y], ...] で指定します',
    '{}: no holes: give holes = [[x, y], ...] in work mm': '{0}：穴がありません：holes = [[x, y], ...]（ワーク座標 mm）を指定してください',
    "{}: objects.{}: an engraving's objects are {}": '{0}：objects.{1}：彫刻のオブジェクトは {2} です',
    'job file {}: operation {} ({}): enabled must be true or false': 'ジョブファイル {0}：加工 {1}（{2}）：enabled は true か false です',
    'job file {}: [setup] gives both blend and sample; give one': 'ジョブファイル {0}：[setup] に blend と sample の両方があります。どちらか一方にしてください',
    'job file {}: [setup] sample {} is not one of {}': 'ジョブファイル {0}：[setup] の sample {1} は {2} のいずれでもありません',
    'job file {}: [setup] text is for the name_plate sample': 'ジョブファイル {0}：[setup] の text は name_plate サンプル用です',
    'job file {}: [setup] arcs must be true or false, got {}': 'ジョブファイル {0}：[setup] の arcs は true か false にしてください（指定値 {1}）',
    '{}: objects.{} = {} is not an object of the scene': '{0}：objects.{1} = {2} はシーンのオブジェクトではありません',
    '{}: settings.{} is not a setting of {}': '{0}：settings.{1} は {2} の設定ではありません',
    '{}: kind {} is not one of {}': '{0}：種類 {1} は {2} のいずれでもありません',
    '{}: no operation gives the stock: begin with one that works on a plate or a part (engrave, carve)':
        '{0}：素材を決める加工がありません。板や部品を加工するもの（engrave、carve）から始めてください',
    'job file {}: no such file': 'ジョブファイル {0}：ファイルがありません',
    'job file {}: a folder, not a job file': 'ジョブファイル {0}：ジョブファイルではなくフォルダーです',
    'job file {}: not UTF-8 text': 'ジョブファイル {0}：UTF-8 のテキストではありません',
    'job file {}: not TOML ({})': 'ジョブファイル {0}：TOML ではありません（{1}）',
    'job file {}: unknown table {}; a job file has [setup] and [[operations]]':
        'ジョブファイル {0}：不明な表 {1}。ジョブファイルにあるのは [setup] と [[operations]] です',
    'job file {}: setup must be a table': 'ジョブファイル {0}：setup は表でなければなりません',
    'job file {}: [setup] has an unknown key {}; the keys are {}': 'ジョブファイル {0}：[setup] に不明なキー {1} があります（キーは {2}）',
    'job file {}: no [[operations]]; a job needs at least one': 'ジョブファイル {0}：[[operations]] がありません。ジョブには少なくとも1つ必要です',
    'job file {}: operation {} must be a table': 'ジョブファイル {0}：加工 {1} は表でなければなりません',
    'job file {}: operation {} has an unknown key {}; the keys are {}': 'ジョブファイル {0}：加工 {1} に不明なキー {2} があります（キーは {3}）',
    'job file {}: operation {} needs a {} (text)': 'ジョブファイル {0}：加工 {1} には {2}（テキスト）が必要です',
    'job file {}: operation {} ({}): {} must be a table': 'ジョブファイル {0}：加工 {1}（{2}）：{3} は表でなければなりません',
    '--each {}: no such file': '--each {0}：ファイルがありません',
    '--each {}: a folder, not a CSV file': '--each {0}：CSV ファイルではなくフォルダーです',
    '--each {}: not UTF-8 text (save the CSV as UTF-8)': '--each {0}：UTF-8 のテキストではありません（CSV を UTF-8 で保存してください）',
    '--each {}: not a CSV file ({})': '--each {0}：CSV ファイルではありません（{1}）',
    '--each {}: empty; the first line names the columns': '--each {0}：空です。1行目に列名を書いてください',
    '--each {}: line 1 has an empty column name': '--each {0}：1行目に空の列名があります',
    '--each {}: line 1 names the column {} twice': '--each {0}：1行目で列 {1} が2回あります',
    '--each {}: no rows under the header line': '--each {0}：見出し行の下に行がありません',
    '--each {}: {} rows; at most {} in one run': '--each {0}：{1} 行あります。1回の実行で最大 {2} 行です',
    '--each {}: line {} has {} values for {} columns': '--each {0}：{1} 行目の値は {2} 個ですが、列は {3} 個です',
    "{}: the job file's line {} asks for {{{{{}}}}}, a column the CSV does not have ({})":
        '{0}：ジョブファイルの {1} 行目が {{{{{2}}}}} を求めていますが、CSV にその列はありません（{3}）',
    '{}: column {} = {} is not a number, and the job file uses it outside quotes (as a number)':
        '{0}：列 {1} = {2} は数値ではありませんが、ジョブファイルは引用符の外（数値として）で使っています',
    'operation kind {} is declared twice': '加工の種類 {0} が2回宣言されています',
    'unknown operation kind {}; the kinds are {}': '不明な加工の種類 {0}（種類は {1}）',
    'tool number {} is the {} in {} but the {} in {}: give one of them another tool number':
        '工具番号 {0} は {2} では {1}、{4} では {3} です。どちらかに別の工具番号を付けてください',
    'two operations are named {}: give each operation its own name': '2つの加工が {0} という名前です。それぞれに別の名前を付けてください',
    "operation {} ({}) runs on {} machines, not on the job's {} machine":
        '加工 {0}（{1}）は {2} の機械用で、ジョブの {3} の機械では使えません',
    'operation {}: settings must be {}, got {}': '加工 {0}：設定は {1} でなければなりません（指定は {2}）',
    'drilling needs a drill, not a {}': '穴あけにはドリルが必要です（{0} ではなく）',
    'drilling: {} must be a positive number, got {}': '穴あけ：{0} は正の数でなければなりません（指定値 {1}）',
    'drilling: {} must be 0 or more, got {}': '穴あけ：{0} は 0 以上でなければなりません（指定値 {1}）',
    "drilling: depth {} mm is deeper than the {}'s {} mm flutes": '穴あけ：深さ {0} mm は {1} の刃長 {2} mm より深いです',
    'drilling: the approach gap {} mm, clearance plane {} mm and safe Z {} mm must rise in that order':
        '穴あけ：アプローチ隙間 {0} mm、クリアランス面 {1} mm、安全 Z {2} mm はこの順に高くなければなりません',
    'holes must be (x, y) pairs in mm, got {}': '穴は mm の (x, y) の組でなければなりません（指定値 {0}）',
    'holes must be a list of (x, y) pairs in mm, got shape {}': '穴は mm の (x, y) の組のリストでなければなりません（形 {0}）',
    'hole {} has a coordinate that is not a number: {}': '穴 {0} の座標に数値でないものがあります：{1}',
    'holes {} and {} are the same point {}': '穴 {0} と {1} は同じ点 {2} です',
    # drilling, cycles and chamfers (issue 29)
    '{}: settings.{} is not a chamfer setting; they are {}': '{0}：settings.{1} は面取りの設定ではありません（設定は {2}）',
    '{}: the V-bit: {}': '{0}：V ビット：{1}',
    '{}: objects.{}: a chamfer takes objects.edges (a curve, Text or mesh)':
        '{0}：objects.{1}：面取りは objects.edges（カーブ、テキストまたはメッシュ）を取ります',
    '{}: no edges: give objects = {{ edges = "<curve, Text or mesh>" }}':
        '{0}：縁がありません：objects = {{ edges = "<カーブ、テキストまたはメッシュ>" }} を指定してください',
    '{}: the edges or the V-bit: {}': '{0}：縁または V ビット：{1}',
    '{}: objects.{}: drilling takes objects.holes (a curve or a mesh)':
        '{0}：objects.{1}：穴あけは objects.holes（カーブまたはメッシュ）を取ります',
    '{}: give the holes as holes = [[x, y], ...] or as objects.holes, not both':
        '{0}：穴は holes = [[x, y], ...] か objects.holes のどちらか一方で指定してください（両方は不可）',
    '{}: settings.{} = {} is not true or false': '{0}：settings.{1} = {2} は true でも false でもありません',
    '{}: settings.{} = {} is not one of {}': '{0}：settings.{1} = {2} は {3} のいずれでもありません',
    '{}: settings.{} = {} is not a whole number': '{0}：settings.{1} = {2} は整数ではありません',
    '{}: objects.holes = {} has no closed curve that is a circle (within {} mm)':
        '{0}：objects.holes = {1} に円である閉じたカーブがありません（許容差 {2} mm）',
    '{}: objects.holes = {} has no vertical cylindrical hole (within {} mm)':
        '{0}：objects.holes = {1} に垂直な円筒の穴がありません（許容差 {2} mm）',
    '{}: objects.holes = {} is a {}; use a curve or a mesh': '{0}：objects.holes = {1} は {2} です。カーブかメッシュを使ってください',
    'drilling cycle kind must be one of {}, got {}': '穴あけサイクルの種類は {0} のいずれかです（指定値 {1}）',
    'drilling cycle retract must be one of {}, got {}': '穴あけサイクルの戻り位置は {0} のいずれかです（指定値 {1}）',
    'drilling cycle: {} is not a number: {}': '穴あけサイクル：{0} が数値ではありません：{1}',
    'drilling cycle: the bottom Z {}, R plane {} and initial Z {} must rise in that order':
        '穴あけサイクル：穴底 Z {0}、R 点 {1}、イニシャル Z {2} はこの順に高くなければなりません',
    'drilling cycle: feed must be positive, got {}': '穴あけサイクル：送りは正でなければなりません（指定値 {0}）',
    "drilling cycle: a peck of {} mm does not fit a {} cycle (peck > 0 with 'peck' alone)":
        "穴あけサイクル：ペック {0} mm は {1} サイクルに合いません（ペック > 0 は 'peck' のときだけ）",
    "drilling cycle: a dwell of {} s does not fit a {} cycle (dwell > 0 with 'dwell' alone)":
        "穴あけサイクル：ドウェル {0} 秒は {1} サイクルに合いません（ドウェル > 0 は 'dwell' のときだけ）",
    'drilling cycle: holes must be finite (x, y) pairs, got shape {}': '穴あけサイクル：穴は有限の (x, y) の組でなければなりません（形 {0}）',
    "drilling cycle: hole {} at X{} Y{} is not fed to Z{} by the operation's moves":
        '穴あけサイクル：X{1} Y{2} の穴 {0} は加工の移動で Z{3} まで送られていません',
    'drilling cycle: a feed move at {} is at none of its holes': '穴あけサイクル：{0} の切削送りはどの穴の位置でもありません',
    'operation {}: cycle must be a DrillCycle or None, got {}': '加工 {0}：cycle は DrillCycle か None でなければなりません（指定は {1}）',
    "operation {}: a drilling cycle's moves are straight, without rotary axes":
        '加工 {0}：穴あけサイクルの移動は直線で、回転軸を動かしません',
    'chamfering needs a V-bit, not a {}': '面取りには V ビットが必要です（{0} ではなく）',
    'chamfer: {} must be 0 or more, got {}': '面取り：{0} は 0 以上でなければなりません（指定値 {1}）',
    'chamfer: give the width or the depth, one of them (width {}, depth {})':
        '面取り：幅か深さのどちらか一方を指定してください（幅 {0}、深さ {1}）',
    'chamfer: {} must be a positive number, got {}': '面取り：{0} は正の数でなければなりません（指定値 {1}）',
    'chamfer: the approach gap {} mm, clearance plane {} mm and safe Z {} mm must rise in that order':
        '面取り：アプローチ隙間 {0} mm、クリアランス面 {1} mm、安全 Z {2} mm はこの順に高くなければなりません',
    'chamfer: a {} mm chamfer with the tip {} mm below it needs the V-bit {} mm wide at the top; the {} is {} mm':
        '面取り：幅 {0} mm の面取りを先端 {1} mm 下で削るには上端で {2} mm 幅の V ビットが必要ですが、{3} は {4} mm です',
    "chamfer: the tip {} mm deep is beyond the {}'s {} mm flutes": '面取り：先端の深さ {0} mm は {1} の刃長 {2} mm を超えています',
    'drilling: depth must be a positive number, got {}': '穴あけ：深さは正の数でなければなりません（指定値 {0}）',
    'drilling: dwell is for holes drilled without pecks (peck = 0); got peck {} mm and dwell {} s':
        '穴あけ：ドウェルはステップ送りなし（peck = 0）の穴用です（ペック {0} mm、ドウェル {1} 秒）',
    'drilling: retract must be one of {}, got {}': '穴あけ：retract は {0} のいずれかです（指定値 {1}）',
    "drilling: order must be 'shortest' or 'given', got {}": "穴あけ：order は 'shortest' か 'given' です（指定値 {0}）",
    'drilling: max_diameter {} mm is below min_diameter {} mm': '穴あけ：max_diameter {0} mm が min_diameter {1} mm より小さいです',
    'helix milling needs a flat end mill, not a {}': 'ヘリカル加工にはフラットエンドミルが必要です（{0} ではなく）',
    'helix milling: {} must be a positive number, got {}': 'ヘリカル加工：{0} は正の数でなければなりません（指定値 {1}）',
    'spot drilling needs a pointed drill that plunges, not a {}': 'もみつけには突っ込めるとがったドリルが必要です（{0} ではなく）',
    'spot drilling: spot_depth must be a positive number, got {}': 'もみつけ：spot_depth は正の数でなければなりません（指定値 {0}）',
    'hole {} at X{} Y{}: {} mm is not wider than the {}; drill it instead':
        'X{1} Y{2} の穴 {0}：{3} mm は {4} より広くありません。ドリルで開けてください',
    "hole {} at X{} Y{}: {} mm deep is more than the {}'s {} mm flutes":
        'X{1} Y{2} の穴 {0}：深さ {3} mm は {4} の刃長 {5} mm を超えています',
    '{} holes but {} diameters, {} bottoms, {} through flags': '穴は {0} 個ですが、直径 {1} 個、穴底 {2} 個、貫通の印 {3} 個です',
    'no hole is between min_diameter {} mm and max_diameter {} mm; the holes are {} mm':
        'min_diameter {0} mm と max_diameter {1} mm の間の穴がありません（穴は {2} mm）',
    "hole at X{} Y{} is {} mm wide, the drill {} mm: drilled at the drill's size (turn helix milling on)":
        'X{0} Y{1} の穴は幅 {2} mm、ドリルは {3} mm です：ドリルの径で開けます（ヘリカル加工をオンにしてください）',
    'operation {}: {}': '加工 {0}：{1}',
    'job file {}: [setup] gives more than one of blend, sample and stock; give one':
        'ジョブファイル {0}：[setup] に blend、sample、stock のうち複数があります。1つにしてください',
    'job file {}: [setup] stock = {} is not [x0, y0, z0, x1, y1, z1] in mm':
        'ジョブファイル {0}：[setup] の stock = {1} は mm の [x0, y0, z0, x1, y1, z1] ではありません',
    'job file {}: [setup] stock = {}: each lower corner value must lie below the upper one':
        'ジョブファイル {0}：[setup] の stock = {1}：下側の角の値はそれぞれ上側より小さくなければなりません',
    'job file {}: [setup] work_zero = {} is not CORNER or CENTER': 'ジョブファイル {0}：[setup] の work_zero = {1} は CORNER でも CENTER でもありません',
    '--set {}: give KEY=VALUE, e.g. --set depth=3': '--set {0}：KEY=VALUE の形で指定してください（例 --set depth=3）',
    '--{}: the drawing has closed outlines on several layers ({}): pick one with --layer':
        '--{0}：図面の複数のレイヤー（{1}）に閉じた輪郭があります。--layer で1つ選んでください',
    'line {}: a drilling cycle in incremental mode (G91) is not followed: {}': '{0} 行目：インクリメンタル（G91）の穴あけサイクルは追えません：{1}',
    'line {}: a drilling cycle with a C word is not followed: {}': '{0} 行目：C ワード付きの穴あけサイクルは追えません：{1}',
    'line {}: {} needs its Z (the bottom) and R (the retract plane) words: {}':
        '{0} 行目：{1} には Z（穴底）と R（R 点）のワードが必要です：{2}',
    'line {}: G83 needs a peck Q greater than 0: {}': '{0} 行目：G83 には 0 より大きいペック量 Q が必要です：{1}',
    'line {}: G82 P{} is a negative dwell: {}': '{0} 行目：G82 P{1} は負のドウェルです：{2}',
    "line {}: the cycle's bottom Z{} lies above its R plane R{}: {}": '{0} 行目：サイクルの穴底 Z{1} が R 点 R{2} より上にあります：{3}',
    'line {}: {} with no feed in effect (a control refuses a cutting move without a feed): {}':
        '{0} 行目：送りが設定されていない {1}（制御装置は送りのない切削移動を受け付けません）：{2}',
    "line {}: a drilling cycle before the tool's XY position is known: {}": '{0} 行目：工具の XY 位置が分かる前の穴あけサイクル：{1}',
    '{}: objects.{}: a carving takes objects.design (the mesh)': '{0}：objects.{1}：彫り込みは objects.design（メッシュ）を取ります',
    "{}: its work zero ({}) is not the job's ({}): the operations of one job share one work zero":
        '{0}：そのワーク原点（{1}）はジョブのもの（{2}）と違います。1つのジョブの加工は1つのワーク原点を共有します',
    '{}: objects.{}: rotary pockets take objects.block (the board)': '{0}：objects.{1}：回転テーブルのポケットは objects.block（板）を取ります',
    '{}: a STEP-NC workplan comes from its file = "...", not objects':
        '{0}：STEP-NC のワークプランはオブジェクトではなく file = "..." から読みます',
    '{}: no file: give file = "part.stp" (an ISO 14649 Part 21 file)':
        '{0}：ファイルがありません：file = "part.stp"（ISO 14649 Part 21 ファイル）を指定してください',
    '{}: settings.{} is not a STEP-NC setting; they are order, enabled': '{0}：settings.{1} は STEP-NC の設定ではありません（設定は order、enabled）',
    '{}: settings.{} = {} is not a list of instance ids': '{0}：settings.{1} = {2} はインスタンス ID のリストではありません',
    '{}: objects.{}: a turn-mill operation takes objects.part': '{0}：objects.{1}：複合旋盤加工は objects.part を取ります',
    'sheet thickness must be a finite number > 0 (mm), got {}': '板厚は 0 より大きい有限の数（mm）でなければなりません（指定値 {0}）',
    'nibbling pitch {} mm: the flat pattern takes {} hits, more than the {} one program may have; raise the pitch':
        'ニブリングピッチ {0} mm：展開図は {1} 回の打ち抜きになり、1つのプログラムに入る {2} 回を超えます。ピッチを大きくしてください',
    'setup sheet: a stock of type {} is neither a box nor a cylinder': '段取りシート：種類 {0} の素材は直方体でも円柱でもありません',
    'setup sheet picture {}: not a PNG image': '段取りシートの画像 {0}：PNG 画像ではありません',
    'setup sheet gate status {}: one of {}': '段取りシートのゲート状態 {0}：{1} のいずれかです',
}

# ----- the job list (operators/joblist.py, issue 28): added to the tables by _build ---------------------
JOBLIST_OPERATORS = {
    "Add Operation": "加工を追加", "Duplicate Operation": "加工を複製", "Remove Operation": "加工を削除",
    "Move Operation": "加工を移動", "Generate Job": "ジョブを生成", "Simulate Job": "ジョブをシミュレーション",
    "Simulate up to Selected": "選択までシミュレーション", "Export Job NC": "ジョブNCを書き出し",
    "Save Job File": "ジョブファイルを保存", "Load Job File": "ジョブファイルを読み込み",
}
JOBLIST_TEXTS = {
    "Add an operation to the end of the job": "ジョブの最後に加工を追加します",
    "Add a copy of the selected operation after it": "選択した加工の複製をその後ろに追加します",
    "Remove the selected operation from the job": "選択した加工をジョブから削除します",
    "Move the selected operation up or down the job (the order it is cut in)":
        "選択した加工をジョブの中で上下に移動します（削る順序）",
    "Plan the job's operations that changed (and those after them) and show every toolpath":
        "変更されたジョブの加工（とその後の加工）を計画し、すべてのツールパスを表示します",
    "Cut the stock with the whole job, or with the operations up to the selected one, and check it":
        "ジョブ全体、または選択した加工までで素材を削り、検査します",
    "Write the job as one NC program: what Generate planned, re-planning only what changed":
        "ジョブを1本のNCプログラムとして書き出します（生成した計画を使い、変更された加工だけを再計画）",
    "Save the job list as a job file (TOML) for batch.py job": "ジョブリストを batch.py job 用のジョブファイル（TOML）に保存します",
    "Load a job file's operations into the job list (its objects by name from this scene)":
        "ジョブファイルの加工をジョブリストに読み込みます（オブジェクトはこのシーンから名前で探します）",
    "Direction": "方向", "Cut it earlier": "先に削る", "Cut it later": "後で削る",
    "Up to Selected": "選択まで",
    "Cut only the operations up to the selected one (the stock as it is then)":
        "選択した加工までだけを削ります（その時点の素材）",
    "Show the rapid moves in the job's toolpath preview": "ジョブのツールパス表示に早送りを表示します",
    "Slot": "枠", "Which of the operation's objects this is": "加工のどのオブジェクトか",
    "Object": "オブジェクト", "The scene object the operation reads for this slot": "この枠で加工が読むシーンのオブジェクト",
    "Enabled": "有効", "Plan and cut this operation (switched off: left out of the program)":
        "この加工を計画して削ります（オフ：プログラムから外します）",
    "Settings": "設定", "The operation's settings by property name (JSON), as a job file keeps them":
        "加工の設定（プロパティ名ごと、JSON）。ジョブファイルと同じ形です",
    "More": "その他", "The operation's other keys (JSON), e.g. a drilling's holes in work mm":
        "加工のその他のキー（JSON）。例：穴あけの穴（ワーク座標 mm）",
    "Kind": "種類", "The operation's kind (engrave, drill ...)": "加工の種類（engrave、drill など）",
    "Tools": "工具", "The tool numbers the operation uses": "加工が使う工具番号",
    "Time": "時間", "Estimated cutting time (min)": "推定加工時間（分）",
    "Warnings of its plan and findings of the last simulation": "計画の警告と最後のシミュレーションの指摘",
    "State": "状態", "Not Planned": "未計画", "Not planned yet: Generate plans it": "まだ計画されていません：生成で計画します",
    "Planned": "計画済み", "Planned: its toolpaths are what Export writes": "計画済み：そのツールパスが書き出されます",
    "Stale": "要再計画", "Changed since it was planned: Generate or Export plans it again":
        "計画後に変更されました：生成または書き出しで再計画します",
    "Planned, with warnings or simulation findings": "計画済み（警告またはシミュレーションの指摘あり）",
    "Failed": "失敗", "Planning it failed: see the report": "計画に失敗しました：レポートを見てください",
    "Surface": "曲面", "Drilling": "穴あけ", "Pecked holes at given centres (job files)": "指定した中心にステップ送りの穴（ジョブファイル）",
    "Holes at given centres or found in curves and meshes (job files)":
        "指定した中心、またはカーブやメッシュで見つけた穴（ジョブファイル）",
    "Chamfer": "面取り", "V-bit chamfer along the top edges of closed outlines (job files)":
        "閉じた輪郭の上端を V ビットで面取り（ジョブファイル）",
    "the job list is empty: add an operation first": "ジョブリストが空です。先に加工を追加してください",
    "save the .blend first: a job file names the .blend its objects come from":
        "先に .blend を保存してください。ジョブファイルはオブジェクトを読む .blend を名前で指定します",
    "Add an operation to the job list first": "先にジョブリストに加工を追加してください",
    "The .blend has unsaved changes: batch reads the saved .blend, save it too":
        ".blend に未保存の変更があります。バッチは保存された .blend を読むので、それも保存してください",
    "nothing re-planned": "再計画なし",
}
JOBLIST_TEMPLATES = {
    "{}: {} is not JSON ({})": "{0}：{1} が JSON ではありません（{2}）",
    "{}: {} must be a table of names and values": "{0}：{1} は名前と値の表にしてください",
    "the value {} cannot be written to a job file": "値 {0} はジョブファイルに書けません",
    "job file {}: operation {} ({}): kind {} is not one of {}":
        "ジョブファイル {0}：加工 {1}（{2}）：種類 {3} は {4} のいずれでもありません",
    "Added {}": "{0} を追加しました",
    "Job planned: about {} min": "ジョブを計画しました：約 {0} 分",
    "Loaded {} operation(s)": "{0} 件の加工を読み込みました",
    "re-planned: {}": "再計画：{0}",
}


# ----- designs from drawing programs (operators/designfile.py, toolpath/engines/svgfile.py, dxffile.py,
# svgpath.py, designshapes.py; issue 29): added to the tables here ------------------------------------
DESIGN_OPERATORS = {"Import Design": "デザインを読み込み"}
DESIGN_OPERATOR_TEXTS = {"Kezuri design (.svg/.dxf)": "Kezuri デザイン (.svg/.dxf)"}
DESIGN_MESSAGES = {
    "Import an SVG or DXF drawing as curves (one object per layer, in mm at the scene's unit scale)":
        "SVG または DXF の図面をカーブとして読み込みます（レイヤーごとに1オブジェクト、シーンの単位スケールで mm）",
    "DXF Scale": "DXF の縮尺",
    "Millimetres per drawing unit of a DXF file without units (a file that gives its units is read in them)":
        "単位のない DXF ファイルの図面単位あたりのミリメートル（単位を持つファイルはその単位で読みます）",
    "no design: give --svg FILE or --dxf FILE": "デザインがありません：--svg FILE または --dxf FILE を指定してください",
}
DESIGN_TEMPLATES = {
    # operators/designfile.py
    '{}: design must be a file name ("logo.svg") or a table with file = "..."':
        '{0}：design はファイル名（"logo.svg"）か file = "..." を持つ表にしてください',
    "{}: design.{} is not a key of a design; they are file, layer, scale, at":
        "{0}：design.{1} は design のキーではありません（キーは file、layer、scale、at）",
    "{}: design.layer must be a layer's name": "{0}：design.layer はレイヤー名にしてください",
    "{}: design.scale = {} is not a number": "{0}：design.scale = {1} は数値ではありません",
    "{}: design.at = {} is not [x, y] in mm": "{0}：design.at = {1} は mm の [x, y] ではありません",
    "{}: design: {}": "{0}：デザイン：{1}",
    "Imported {} closed and {} open path(s) from {}": "{2} から閉じた経路 {0} 本と開いた経路 {1} 本を読み込みました",
    "{}: not a design file: give an .svg or .dxf file": "{0}：デザインファイルではありません。.svg か .dxf を指定してください",
    "--scale {}: a scale is for a DXF file without units; an SVG gives its size":
        "--scale {0}：縮尺は単位のない DXF ファイル用です。SVG は自身の大きさを持ちます",
    "{}: no layer {}; its layers are {}": "{0}：レイヤー {1} はありません（レイヤーは {2}）",
    "DXF Scale = {}: give a positive number of mm per drawing unit": "DXF の縮尺 = {0}：図面単位あたりの正の mm 数を指定してください",
    "{}: no closed outline in the layers asked for": "{0}：指定したレイヤーに閉じた輪郭がありません",
    # toolpath/engines/designshapes.py
    "{}: a coordinate is not a finite number (NaN or infinity)": "{0}：有限でない座標があります（NaN または無限大）",
    "{}: a point lies {} mm from the origin (more than {} mm): are the units right?":
        "{0}：点が原点から {1} mm にあります（{2} mm を超えています）。単位は正しいですか？",
    "{}: the design has more than {} points after flattening; simplify it in the drawing program":
        "{0}：折れ線化したデザインの点が {1} 個を超えます。作図ソフトで簡略化してください",
    "{}: an open piece (its ends do not meet another's within {} mm)":
        "{0}：開いた線です（端点が {1} mm 以内で他の線とつながりません）",
    # toolpath/engines/svgfile.py
    "{}: line {}: entity {}: external and parameter entities are refused":
        "{0}：{1} 行目：エンティティ {2}：外部エンティティとパラメータエンティティは受け付けません",
    "{}: line {}: entity {}: an entity that refers to others or holds markup is refused (it can expand without end)":
        "{0}：{1} 行目：エンティティ {2}：他を参照する、またはマークアップを含むエンティティは受け付けません（際限なく展開されうるため）",
    "{}: line {}: entity {}: more than {} entity declarations are refused":
        "{0}：{1} 行目：エンティティ {2}：{3} 個を超えるエンティティ宣言は受け付けません",
    "{}: line {}: elements nested more than {} deep": "{0}：{1} 行目：要素の入れ子が {2} 段を超えています",
    "{}: line {}: an external entity is refused": "{0}：{1} 行目：外部エンティティは受け付けません",
    "{}: not well-formed XML ({}, line {}){}": "{0}：正しい XML ではありません（{1}、{2} 行目）{3}",
    "{}: not an SVG drawing (the root element is <{}>)": "{0}：SVG 図面ではありません（ルート要素が <{1}>）",
    "{}: {} is missing": "{0}：{1} がありません",
    "{}: {}={} is not a length": "{0}：{1}={2} は長さではありません",
    "{}: {}={} is not a finite number": "{0}：{1}={2} は有限の数ではありません",
    "{}: {}={}: a percentage is not a length in a drawing": "{0}：{1}={2}：パーセントは図面の長さになりません",
    "{}: viewBox={} is not four numbers with a positive width and height":
        "{0}：viewBox={1} は幅と高さが正の4つの数ではありません",
    "{}: more than {} elements drawn (uses of uses?)": "{0}：描く要素が {1} 個を超えます（use の入れ子？）",
    "{}: elements and uses nested more than {} deep": "{0}：要素と use の入れ子が {1} 段を超えています",
    "{}: href={} names no element of the file": "{0}：href={1} はファイル内のどの要素も指していません",
    "{}: href={} uses itself (through {})": "{0}：href={1} が自分自身を使っています（経由：{2}）",
    "{}: points must be pairs of numbers": "{0}：points は数の組にしてください",
    "{}: a compressed SVG (.svgz): save it as plain SVG": "{0}：圧縮 SVG（.svgz）です。通常の SVG で保存してください",
    "{}: no such file": "{0}：ファイルがありません",
    "{}: {} bytes, more than a drawing of {} bytes is refused": "{0}：{1} バイト。{2} バイトを超える図面は受け付けません",
    "{}: no lines or curves to cut ({})": "{0}：削る線や曲線がありません（{1}）",
    "{}: no lines or curves to cut": "{0}：削る線や曲線がありません",
    "{}: a text, skipped (convert it to paths in the drawing program)":
        "{0}：テキストは読み飛ばしました（作図ソフトでパスに変換してください）",
    "{}: an image, skipped": "{0}：画像は読み飛ばしました",
    "{}: its transform flattens it to nothing, skipped": "{0}：変形で大きさがなくなるため読み飛ばしました",
    # toolpath/engines/svgpath.py (the problems inside "path data: ..." are templates of their own)
    "{}: path data: {} at character {} (near {})": "{0}：パスデータ：{2} 文字目で {1}（付近 {3}）",
    "a number is missing": "数値がありません",
    "{} is not a number": "{0} は数値ではありません",
    "the number {} is too large": "数値 {0} が大きすぎます",
    "an arc flag must be 0 or 1": "円弧のフラグは 0 か 1 にしてください",
    "path data must begin with a moveto (M or m)": "パスデータは moveto（M または m）で始めてください",
    "a number after Z (a new subpath begins with M)": "Z の後に数値があります（新しいサブパスは M で始めます）",
    "{} is neither a command nor a number": "{0} はコマンドでも数値でもありません",
    "{}: transform {}: cannot read it from character {}": "{0}：transform {1}：{2} 文字目から読めません",
    "{}: transform {}: {}({}) holds something not a number": "{0}：transform {1}：{2}({3}) に数値でないものがあります",
    "{}: transform {}: a number is too large": "{0}：transform {1}：数値が大きすぎます",
    "{}: transform {}: {} takes {} numbers, got {}": "{0}：transform {1}：{2} は {3} 個の数値をとります（{4} 個あります）",
    # toolpath/engines/dxffile.py
    "{}: {} lines, an odd number: a group code without its value at line {} (is the file cut short?)":
        "{0}：{1} 行（奇数）：{2} 行目のグループコードに値がありません（ファイルが途中で切れていませんか？）",
    "{}: line {}: group code {} is not a whole number (not an ASCII DXF file?)":
        "{0}：{1} 行目：グループコード {2} が整数ではありません（ASCII DXF ファイルではない？）",
    "{}: line {}: a SECTION without its name": "{0}：{1} 行目：名前のない SECTION です",
    "{}: the {} section from line {} has no ENDSEC (is the file cut short?)":
        "{0}：{2} 行目からの {1} セクションに ENDSEC がありません（ファイルが途中で切れていませんか？）",
    "{}: no ENTITIES section (not a DXF drawing, or cut short?)":
        "{0}：ENTITIES セクションがありません（DXF 図面ではない、または途中で切れている？）",
    "{}: its extrusion ({}, {}, {}) is not along Z: it does not lie in the drawing's plane":
        "{0}：押し出し方向 ({1}, {2}, {3}) が Z 方向ではありません：図面の平面上にありません",
    "{}: {} control point X values but {} Y values": "{0}：制御点の X が {1} 個、Y が {2} 個です",
    "{}: neither control points nor two fit points": "{0}：制御点も2つ以上のフィット点もありません",
    "{}: degree {} with {} control points": "{0}：次数 {1} に制御点が {2} 個です",
    "{}: {} knots for {} control points of degree {} (needs {}, never decreasing)":
        "{0}：次数 {3} の制御点 {2} 個にノットが {1} 個です（減少しない {4} 個が必要）",
    "{}: the weights must be one positive number per control point": "{0}：重みは制御点ごとに1つの正の数にしてください",
    "{}: a vertex has an X (10) but no Y (20)": "{0}：X (10) があって Y (20) がない頂点があります",
    "{}: more than {} entities drawn (inserts of inserts?)": "{0}：描くエンティティが {1} 個を超えます（INSERT の入れ子？）",
    "{}: block {} is not in the BLOCKS section": "{0}：ブロック {1} が BLOCKS セクションにありません",
    "{}: block {} inserts itself (through {})": "{0}：ブロック {1} が自分自身を挿入しています（経由：{2}）",
    "{}: a scale of 0 flattens block {} to nothing": "{0}：尺度 0 ではブロック {1} の大きさがなくなります",
    "{}: {} columns x {} rows of block {}": "{0}：ブロック {3} の {1} 列 x {2} 行",
    "{}: radius {} must be > 0": "{0}：半径 {1} は 0 より大きくしてください",
    "{}: the major axis ({}, {}) and ratio {} draw no ellipse": "{0}：長軸 ({1}, {2}) と比率 {3} では楕円になりません",
    "{}: a binary DXF: save it as ASCII DXF": "{0}：バイナリ DXF です。ASCII DXF で保存してください",
    "{}: line {}: $INSUNITS = {} is not a whole number": "{0}：{1} 行目：$INSUNITS = {2} が整数ではありません",
    "{}: $INSUNITS = {}: units this reader does not take (mm, cm, m, inches, feet ...)":
        "{0}：$INSUNITS = {1}：読めない単位です（mm、cm、m、インチ、フィートなど）",
    "{}: the file says its units ({}): a scale is only for a file without units":
        "{0}：ファイルが単位（{1}）を持っています。縮尺は単位のないファイル専用です",
    "{}: scale {} must be a positive number of mm per drawing unit": "{0}：縮尺 {1} は図面単位あたりの正の mm 数にしてください",
    "{}: group {} is missing": "{0}：グループ {1} がありません",
    "{}: line {}: group {} = {} is not a number": "{0}：{1} 行目：グループ {2} = {3} は数値ではありません",
    "{}: line {}: group {} = {} is not a finite number": "{0}：{1} 行目：グループ {2} = {3} は有限の数ではありません",
    "{}: no units in the file: read as {} mm per drawing unit": "{0}：ファイルに単位がありません：図面単位あたり {1} mm として読みました",
    "{}: skipped {} entities on the layer {}, which is off or frozen, first at line {}":
        "{0}：非表示またはフリーズのレイヤー {2} のエンティティ {1} 個を読み飛ばしました（最初は {3} 行目）",
    "{}: skipped {} {} (draws no cutting line), first at line {}":
        "{0}：{2} を {1} 個読み飛ばしました（削る線を描きません、最初は {3} 行目）",
    "{}: skipped {} {} in paper space (a sheet's frame or title block), first at line {}":
        "{0}：ペーパー空間の {2} を {1} 個読み飛ばしました（図枠や表題欄、最初は {3} 行目）",
    "{}: skipped {} POLYLINE meshes (3-D surfaces, not lines), first at line {}":
        "{0}：POLYLINE メッシュ {1} 個を読み飛ばしました（線ではなく3次元の面、最初は {2} 行目）",
    "{}: skipped {} {} (an entity this reader does not know), first at line {}":
        "{0}：{2} を {1} 個読み飛ばしました（このリーダーが知らないエンティティ、最初は {3} 行目）",
}
OPERATOR_LABELS.update(DESIGN_OPERATORS)
OPERATOR_TEXTS.update(DESIGN_OPERATOR_TEXTS)
MESSAGES.update(DESIGN_MESSAGES)
MESSAGE_TEMPLATES.update(DESIGN_TEMPLATES)
NESTED["{}: path data: {} at character {} (near {})"] = (1,)
NESTED["{}: design: {}"] = (1,)
# pocketing (issue 29)
POCKET_TEXTS = {"Pocket": "ポケット", "Clear closed regions with islands to a flat floor (job files)":
                "島のある閉じた領域を平らな底まで削ります（ジョブファイル）"}
POCKET_NESTED = {"{}: the pocket: {}": (1,), "{}: the end mill: {}": (1,)}
POCKET_TEMPLATES = {
    "{}: the pocket: {}": "{0}：ポケット：{1}",
    "{}: the end mill: {}": "{0}：エンドミル：{1}",
    "{}: settings.{} is not a pocket setting; they are {}": "{0}：settings.{1} はポケットの設定ではありません（設定は {2}）",
    "{}: settings.{} = {} is not a word": "{0}：settings.{1} = {2} は語ではありません",
    "{}: settings.{} = {} is not true or false": "{0}：settings.{1} = {2} は true でも false でもありません",
    "{}: settings.{} = {} is not a whole number": "{0}：settings.{1} = {2} は整数ではありません",
    "{}: rest machining needs settings.rest_diameter": "{0}：残り削りには settings.rest_diameter が必要です",
    "{}: objects.{}: a pocket's objects are {}": "{0}：objects.{1}：ポケットのオブジェクトは {2} です",
    '{}: no region: give objects = {{ region = "<curve, Text or mesh>" }}':
        '{0}：領域がありません：objects = {{ region = "<カーブ、テキストまたはメッシュ>" }} を指定してください',
    "{}: the {} mm end mill's {} mm helix does not fit in the region at X{} Y{}, nor a ramp along the path there "
    "({} mm long, less than {} mm)":
        "{0}：{1} mm エンドミルの {2} mm のヘリカルが X{3} Y{4} で領域に収まらず、そこの経路に沿うランプも入りません"
        "（長さ {5} mm、{6} mm 未満）",
    "{}: the {} mm end mill's ramp does not fit in the region at X{} Y{}: the path there is {} mm long, less than {} mm":
        "{0}：{1} mm エンドミルのランプが X{2} Y{3} で領域に入りません：そこの経路は {4} mm で、{5} mm 未満です",
    "{}: the {} mm end mill cannot enter at X{} Y{} (a {} mm path): left uncut there":
        "{0}：{1} mm エンドミルは X{2} Y{3} に入れません（経路 {4} mm）：そこは削り残します",
    "{}: the {} mm end mill's {} mm helix does not fit at X{} Y{}; ramped along the path":
        "{0}：{1} mm エンドミルの {2} mm のヘリカルが X{3} Y{4} に収まりません。経路に沿ってランプで入ります",
    "more than {} rings at a {} mm stepover": "ステップオーバー {1} mm ではリングが {0} 本を超えます",
    "{}: offset rings {} mm apart (the tool's radius), not the stepover {} mm: rings further apart leave material "
    "between them":
        "{0}：オフセットのリングはステップオーバー {2} mm ではなく {1} mm（工具半径）間隔です。間隔が広いとリングの間に"
        "材料が残ります",
    "{}: rest machining: the {} mm end mill finds nothing the {} mm one left":
        "{0}：残り削り：{2} mm エンドミルの削り残しで {1} mm エンドミルが削れる所はありません",
    "{}: {} must be a flat end mill, not a {}": "{0}：{1} はフラットエンドミルにしてください（{2} ではなく）",
    "{}: {} must be a number, got {}": "{0}：{1} は数値にしてください（指定値 {2}）",
    "{}: {} must be more than 0, got {}": "{0}：{1} は 0 より大きくしてください（指定値 {2}）",
    "{}: {} must be 0 or more, got {}": "{0}：{1} は 0 以上にしてください（指定値 {2}）",
    "{}: strategy must be one of {}, got {}": "{0}：strategy は {1} のいずれかにしてください（指定値 {2}）",
    "{}: entry must be one of {}, got {}": "{0}：entry は {1} のいずれかにしてください（指定値 {2}）",
    "{}: ramp_angle must be from {} to {} degrees, got {}": "{0}：ramp_angle は {1}〜{2} 度にしてください（指定値 {3}）",
    "{}: a stepover of {} mm over {} levels cuts more than {} km: raise the stepover or the step-down":
        "{0}：ステップオーバー {1} mm で {2} 段を削ると {3} km を超えます。ステップオーバーかステップダウンを大きくしてください",
    "{}: {} must be at least {} mm, got {}": "{0}：{1} は {2} mm 以上にしてください（指定値 {3}）",
    "{}: depth {} mm at a {} of {} mm makes more than {} levels": "{0}：深さ {1} mm を {2} {3} mm で削ると {4} 段を超えます",
    "{}: helix_diameter must be 0 (no helix) or from {} to {} mm, got {}":
        "{0}：helix_diameter は 0（ヘリカルなし）か {1}〜{2} mm にしてください（指定値 {3}）",
    "{}: stepover {} mm is more than the {}'s diameter: material would stand between the paths":
        "{0}：stepover {1} mm は {2} の直径より大きいです：経路の間に材料が残ります",
    "{}: rest_stepover {} mm is more than the {}'s diameter": "{0}：rest_stepover {1} mm は {2} の直径より大きいです",
    "{}: depth {} mm is deeper than the {}'s {} mm flutes": "{0}：深さ {1} mm は {2} の刃長 {3} mm より深いです",
    "{}: rest_tool ({}) must be smaller than the tool ({})": "{0}：rest_tool（{1}）は tool（{2}）より小さくしてください",
    "{}: depth {} mm is deeper than the rest tool's {} mm flutes": "{0}：深さ {1} mm は残り削り工具の刃長 {2} mm より深いです",
    "{}: rest_tool and tool have the same tool number {}": "{0}：rest_tool と tool の工具番号 {1} が同じです",
    "{}: {} {} mm is left by roughing but {} is off: no pass would take it":
        "{0}：荒削りが {1} {2} mm を残しますが {3} がオフです：それを削るパスがありません",
    "{}: wall_allowance {} mm must be less than the tool's radius {} mm (one finishing ring takes it)":
        "{0}：wall_allowance {1} mm は工具半径 {2} mm より小さくしてください（仕上げのリング1周で削ります）",
    "{}: floor_allowance {} mm must be less than the depth {} mm": "{0}：floor_allowance {1} mm は深さ {2} mm より小さくしてください",
    "{}: clearance_z {} mm and safe_z {} mm must be above the stock's top and rise in that order":
        "{0}：clearance_z {1} mm と safe_z {2} mm は素材上面より上で、この順に高くしてください",
    "{}: the region must be a list of closed loops of (x, y) points": "{0}：領域は (x, y) 点の閉じたループのリストにしてください",
    "{}: the region has no closed loop": "{0}：領域に閉じたループがありません",
    "{}: loop {} encloses no area (less than {} mm^2)": "{0}：ループ {1} は面積を囲んでいません（{2} mm^2 未満）",
    "{}: loop {} is not a list of (x, y) points": "{0}：ループ {1} は (x, y) 点のリストではありません",
    "{}: loop {} crosses itself: draw it as separate closed loops":
        "{0}：ループ {1} が自己交差しています。別々の閉じたループに描いてください",
    "{}: loop {} crosses itself at X{} Y{}: draw it as separate closed loops":
        "{0}：ループ {1} が X{2} Y{3} で自己交差しています。別々の閉じたループに描いてください",
    "{}: the loops enclose no area (even-odd: each loop inside another is an island)":
        "{0}：ループが面積を囲んでいません（偶奇規則：他のループの内側のループは島です）",
    "{}: the {} mm end mill with the {} mm wall allowance does not fit in the region (X{}..{} Y{}..{})":
        "{0}：壁の取り代 {2} mm を付けた {1} mm エンドミルは領域（X{3}〜{4} Y{5}〜{6}）に入りません",
    "{}: the {} mm end mill does not fit in the region (X{}..{} Y{}..{})":
        "{0}：{1} mm エンドミルは領域（X{2}〜{3} Y{4}〜{5}）に入りません",
}


# The router kinds' settings panels in the job list (issue 29: profile, pocket, drill, chamfer; kindsettings.py)
ROUTER_PANEL_TEXTS = {
    # panel labels
    "Cut": "切削", "Tabs": "タブ", "Tool & Feeds": "工具と送り", "Lead-In & Out": "アプローチと退避",
    "Clearing": "除去加工", "Finishing": "仕上げ", "Rest Machining": "残り削り", "Holes": "穴",
    "Drill & Feeds": "ドリルと送り", "Helix & Spot": "ヘリカルとセンタ穴", "Edges": "エッジ",
    # property names
    "Tool Number": "工具番号", "Side": "加工側", "Climb Milling": "ダウンカット", "Breakthrough": "突き抜け量",
    "Ramp Angle": "ランプ角度", "Tab Spacing": "タブ間隔", "Tab Width": "タブ幅", "Tab Height": "タブ高さ",
    "Tab Shape": "タブ形状", "Lead": "アプローチ", "Lead Radius": "アプローチ半径", "Stepover": "ステップオーバー",
    "Strategy": "加工方法", "Angle": "角度", "Entry": "進入", "Helix Diameter": "ヘリカル径",
    "Finish Walls": "壁の仕上げ", "Wall Allowance": "壁の取り代", "Finish Floor": "底の仕上げ",
    "Floor Allowance": "底の取り代", "Entry Feed": "進入送り", "Rest Diameter": "残り削り工具径",
    "Rest Tool": "残り削り工具", "Rest Flutes": "残り削り刃長", "Rest Stepover": "残り削りピッチ",
    "Rest Step Down": "残り削り切込み", "Rest Spindle": "残り削り回転数", "Rest Feed": "残り削り送り",
    "Peck": "ペック量", "Dwell": "ドウェル", "Retract": "復帰位置", "Order": "加工順",
    "Min Diameter": "最小径", "Max Diameter": "最大径", "Tolerance": "許容差", "Helix Milling": "ヘリカル加工",
    "Mill Tool": "エンドミル番号", "Mill Diameter": "エンドミル径", "Mill Flutes": "エンドミル刃長",
    "Mill Spindle": "エンドミル回転数", "Mill Feed": "エンドミル送り", "Helix Pitch": "ヘリカルピッチ",
    "Spot Drill": "センタ穴ドリル", "Spot Depth": "センタ穴深さ", "Spot Tool": "センタ穴工具",
    "Spot Diameter": "センタ穴ドリル径", "Width": "幅", "Tip Gap": "先端すき間",
    # enum items
    "Outside": "外側", "Inside": "内側", "On the Line": "線上", "Flat": "平ら", "Triangle": "三角",
    "Arc": "円弧", "Line": "直線", "None": "なし", "Offset": "オフセット", "Zigzag": "ジグザグ",
    "Helix": "ヘリカル", "Ramp": "ランプ", "Initial Level": "イニシャル点", "R Plane": "R点",
    "Shortest": "最短", "As Given": "指定順",
    "Cut the part out: the tool runs outside the outline": "部品を切り抜きます：工具は輪郭の外側を通ります",
    "Cut a hole: the tool runs inside the outline": "穴を切ります：工具は輪郭の内側を通ります",
    "The tool's centre on the outline": "工具中心を輪郭上に置きます",
    "A flat top with 45 degree ends": "上面が平らで両端が45度",
    "A ridge as wide and high as the tab": "タブの幅と高さの山形",
    "A quarter arc in the waste": "捨て側の1/4円弧", "A line along the normal in the waste": "捨て側の法線方向の直線",
    "Straight onto the contour": "輪郭へ直接",
    "Rings from the inside out along the walls": "内側から外側へ壁に沿うリング",
    "A raster at the angle, then a ring along the walls": "角度方向の往復走査のあと壁に沿うリング",
    "A helix inside the region (a ramp where none fits)": "領域内のヘリカル（入らない所はランプ）",
    "A ramp along the path": "経路に沿うランプ",
    "The clearance plane (G98)": "クリアランス面（G98）", "The R plane (G99)": "R点（G99）",
    "Nearest neighbour, then 2-opt": "最近傍のあと 2-opt", "As listed": "並べた順",
    # descriptions
    "Which side of the outline the tool cuts": "輪郭のどちら側を削るか",
    "Climb milling (off: conventional)": "ダウンカット（オフ：アップカット）",
    "Depth below the top; 0: through the stock and the breakthrough (mm)":
        "上面からの深さ。0：素材を貫通し突き抜け量まで (mm)",
    "How far below the stock a cut through goes (mm)": "貫通する切削が素材の下へ出る量 (mm)",
    "Deepest cut of one level (mm)": "1段の最大切込み (mm)",
    "Left for the finishing pass; 0: no finishing pass (mm)": "仕上げパス用の取り代。0：仕上げパスなし (mm)",
    "Feed down the ramps (mm/min)": "ランプを下る送り (mm/min)",
    "Slope of the ramp entry (degrees)": "ランプ進入の傾き (度)",
    "Tabs on every contour (0: none, or by spacing)": "各輪郭のタブ数（0：なし、または間隔で指定）",
    "A tab every ... round each contour; 0: by count (mm)": "各輪郭を回るタブの間隔。0：個数で指定 (mm)",
    "Width of a tab along the contour (mm)": "輪郭に沿ったタブの幅 (mm)",
    "Height of a tab above the cut's bottom (mm)": "切削底からのタブの高さ (mm)",
    "The tab's profile along the contour": "輪郭に沿ったタブの形",
    "How the finishing pass comes onto the contour and leaves it": "仕上げパスが輪郭に入り、離れる方法",
    "The lead's radius or length (mm)": "アプローチの半径または長さ (mm)",
    "The end mill's tool number (T word)": "エンドミルの工具番号（T ワード）",
    "The end mill's diameter (mm)": "エンドミルの直径 (mm)",
    "The end mill's flute length (mm)": "エンドミルの刃長 (mm)",
    "The end mill's spindle speed (rpm)": "エンドミルの主軸回転数 (rpm)",
    "The end mill's feed (mm/min)": "エンドミルの送り (mm/min)",
    "Depth of the floor below the top (mm)": "上面からの底の深さ (mm)",
    "Between neighbouring paths, at most the diameter (mm)": "隣り合う経路の間隔、直径以下 (mm)",
    "How the region is cleared": "領域の削り方",
    "Zigzag: direction of the raster from +X (degrees)": "ジグザグ：+X からの走査方向 (度)",
    "How each level is entered": "各段への進入方法",
    "Of the helix the tool's centre follows (mm)": "工具中心が通るヘリカルの径 (mm)",
    "Slope of the helix and the ramps (degrees)": "ヘリカルとランプの傾き (度)",
    "A ring along every wall at the end": "最後にすべての壁に沿うリング",
    "Left on the walls by roughing (mm)": "荒削りで壁に残す量 (mm)",
    "A pass over the floor at the full depth": "最終深さで底を削るパス",
    "Left on the floor by roughing (mm)": "荒削りで底に残す量 (mm)",
    "Feed down the helices and ramps (mm/min)": "ヘリカルとランプを下る送り (mm/min)",
    "Height where the operation starts and ends (mm)": "工程の開始と終了の高さ (mm)",
    "A smaller end mill for what the tool cannot reach; 0: no rest machining (mm)":
        "工具が届かない所を削る小径エンドミル。0：残り削りなし (mm)",
    "The rest end mill's tool number; 0: the next after the tool's": "残り削りエンドミルの工具番号。0：工具の次の番号",
    "The rest end mill's flute length; 0: the tool's (mm)": "残り削りエンドミルの刃長。0：工具と同じ (mm)",
    "Between the rest end mill's paths (mm)": "残り削りエンドミルの経路間隔 (mm)",
    "The rest end mill's deepest cut (mm)": "残り削りエンドミルの最大切込み (mm)",
    "The rest end mill's spindle speed (rpm)": "残り削りエンドミルの主軸回転数 (rpm)",
    "The rest end mill's feed (mm/min)": "残り削りエンドミルの送り (mm/min)",
    "The drill's tool number (T word)": "ドリルの工具番号（T ワード）",
    "The drill's diameter (mm)": "ドリルの直径 (mm)", "The drill's flute length (mm)": "ドリルの刃長 (mm)",
    "Depth to the tip below the top (holes found in a mesh bring their own) (mm)":
        "上面から先端までの深さ（メッシュで見つけた穴はその深さ） (mm)",
    "Deepest feed of one peck; 0: no pecking (mm)": "1回のペックの最大送り量。0：ペックなし (mm)",
    "Time at the bottom of a hole drilled without pecks (s)": "ペックなしの穴の底での停止時間 (s)",
    "Where the drill goes between holes": "穴と穴の間でドリルが戻る位置",
    "The order the holes are drilled in": "穴をあける順序",
    "Feed down the hole (mm/min)": "穴を下る送り (mm/min)",
    "Below a through hole, beyond the drill's point (mm)": "通し穴の下、ドリル先端部の先 (mm)",
    "Holes found in the model: only those this wide (mm)": "モデルで見つけた穴：この径以上のみ (mm)",
    "Holes found in the model: at most this wide; 0: any (mm)": "モデルで見つけた穴：この径以下。0：制限なし (mm)",
    "How far a found circle's points may lie off the circle (mm)": "見つけた円の点が円から外れてよい距離 (mm)",
    "Mill holes wider than the drill along a helix": "ドリルより大きい穴をヘリカルで削る",
    "Down per turn of the helix (mm)": "ヘリカル1周の下降量 (mm)",
    "A spot drill pass at every hole first": "最初に各穴へセンタ穴ドリル",
    "To the spot drill's tip (mm)": "センタ穴ドリルの先端まで (mm)",
    "The spot drill's tool number (T word)": "センタ穴ドリルの工具番号（T ワード）",
    "The spot drill's diameter (mm)": "センタ穴ドリルの直径 (mm)",
    "The V-bit's tool number (T word)": "Vビットの工具番号（T ワード）",
    "The V-bit's diameter (mm)": "Vビットの直径 (mm)", "The V-bit's flute length (mm)": "Vビットの刃長 (mm)",
    "Across the top, from the edge into the material; 0: from the depth (mm)":
        "上面でエッジから材料側への幅。0：深さから決める (mm)",
    "Down the wall; 0: from the width (mm)": "壁に沿った深さ。0：幅から決める (mm)",
    "The tip below the chamfer, in the waste (mm)": "面取りの下、捨て側での先端の位置 (mm)",
    "chamfer: no holes: give holes = [[x, y, diameter], ...] in work mm":
        "面取り：穴がありません。holes = [[x, y, 直径], ...] をワーク座標 mm で指定してください",
    "chamfer: no edges and no holes to chamfer": "面取り：面取りするエッジも穴もありません",
    # the kinds' descriptions (the job list's Add menu)
    "Cut along an outline, inside, outside or on it, with tabs": "輪郭に沿って内側・外側・線上を切削、タブ付き",
    "Clear closed regions with islands to a flat floor": "島のある閉じた領域を平らな底まで削ります",
    "Holes at given centres or found in curves and meshes": "指定した中心、またはカーブやメッシュで見つけた穴",
    "V-bit chamfer along the top edges of closed outlines and round holes":
        "閉じた輪郭と丸穴の上端を V ビットで面取り",
}


def _build() -> dict:
    messages: dict = {}
    for table in (PROPERTY_TEXTS, PANEL_TEXTS, OPERATOR_DESCRIPTIONS, MESSAGES):
        for english, japanese in table.items():
            messages[(DEFAULT, english)] = japanese
    for english, japanese in (*JOBLIST_TEXTS.items(), *POCKET_TEXTS.items(), *ROUTER_PANEL_TEXTS.items(), *TOOLLIB_TEXTS.items()):
        messages.setdefault((DEFAULT, english), japanese)
    from .. import post
    for cls in post.posts():     # each post declares its own Japanese label and description
        for english, japanese in ((cls.label, cls.label_ja), (cls.description, cls.description_ja)):
            if japanese:
                messages.setdefault((DEFAULT, english), japanese)
    for table in (OPERATOR_LABELS, OPERATOR_TEXTS, JOBLIST_OPERATORS, TOOLLIB_OPERATORS):
        for english, japanese in table.items():
            messages[(OPERATOR, english)] = japanese
            # A panel may share an operator's label ("Pipe Elbow"): the panel's wording wins in "*".
            messages.setdefault((DEFAULT, english), japanese)
    return {LOCALE: messages}


# Profile / cut-out (issue 29): the job files' profile, its settings and refusals
PROFILE_TEXTS = {
    "Profile": "輪郭加工",
    "Shape": "形状",                  # the job list row's object slot

    "Cut along an outline, inside, outside or on it, with tabs (job files)":
        "輪郭に沿って内側・外側・線上を切削、タブ付き（ジョブファイル）",
    "profile: give tab_count or tab_spacing, not both": "輪郭加工：tab_count か tab_spacing のどちらか一方を指定してください",
    "profile: give tab positions (tabs) or tab_count / tab_spacing, not both":
        "輪郭加工：タブ位置（tabs）か tab_count / tab_spacing のどちらか一方を指定してください",
    "profile: allowance leaves material beside the outline: give it with side inside or outside, not on":
        "輪郭加工：allowance は輪郭の横に取り代を残します。side が inside か outside のときに指定してください（on では不可）",
}
PROFILE_TEMPLATES = {
    "{}: settings.{} is not a profile setting; they are {}": "{0}：settings.{1} は輪郭加工の設定ではありません（設定は {2}）",
    "{}: settings.{} = {} is not a word": "{0}：settings.{1} = {2} は語（文字列）ではありません",
    "{}: settings.climb = {} is not true or false": "{0}：settings.climb = {1} は true でも false でもありません",
    "{}: settings.{} = {} is not a whole number": "{0}：settings.{1} = {2} は整数ではありません",
    "{}: the end mill: {}": "{0}：エンドミル：{1}",
    "{}: the profile: {}": "{0}：輪郭加工：{1}",
    "{}: tabs must be a list of [x, y] points in work mm": "{0}：tabs はワーク座標 mm の [x, y] 点のリストにしてください",
    "{}: tabs[{}] = {} is not an [x, y] point in mm": "{0}：tabs[{1}] = {2} は mm の [x, y] 点ではありません",
    "{}: objects.{}: a profile's objects are shape and plate": "{0}：objects.{1}：輪郭加工のオブジェクトは shape と plate です",
    '{}: no shape: give objects = {{ shape = "..." }} (a closed curve, Text or mesh)':
        '{0}：形状がありません。objects = {{ shape = "..." }}（閉じたカーブ、テキスト、メッシュ）を指定してください',
    "{}: the outline crosses itself at ({}, {}): a profile needs closed outlines that do not cross":
        "{0}：輪郭が ({1}, {2}) で自己交差しています。輪郭加工には交差しない閉じた輪郭が必要です",
    "{}: no closed outline to profile": "{0}：輪郭加工する閉じた輪郭がありません",
    "profile: ramp_angle must be more than 0 and at most {} degrees, got {}":
        "輪郭加工：ramp_angle は 0 より大きく {0} 度以下にしてください（指定値 {1}）",
    "profile: tab_count must be a whole number 0 or more, got {}": "輪郭加工：tab_count は 0 以上の整数にしてください（指定値 {0}）",
    "profile: step_down {} mm is more than the {}'s diameter: it would break":
        "輪郭加工：step_down {0} mm が {1} の直径を超えています。工具が折れます",
    "profile: the stock's thickness must be more than 0 mm, got {}": "輪郭加工：素材の厚さは 0 mm より大きくしてください（指定値 {0}）",
    "profile: depth must be more than 0 mm, got {}": "輪郭加工：depth は 0 mm より大きくしてください（指定値 {0}）",
    "profile: depth {} mm goes deeper than the {} mm stock and its {} mm breakthrough: into the table":
        "輪郭加工：depth {0} mm は素材厚 {1} mm と突き抜け {2} mm より深く、テーブルを削ります",
    "profile: step_down {} mm makes more than {} levels down {} mm":
        "輪郭加工：step_down {0} mm では深さ {2} mm までの段数が {1} を超えます",
    "profile: depth {} mm is deeper than the {}'s {} mm flutes": "輪郭加工：depth {0} mm が {1} の刃長 {2} mm より深いです",
    "profile: approach_gap {} mm, clearance_z {} mm and safe_z {} mm must rise in that order":
        "輪郭加工：approach_gap {0} mm、clearance_z {1} mm、safe_z {2} mm はこの順に高くしてください",
    "profile: tab_height {} mm reaches the stock's top (the cut is {} mm deep there)":
        "輪郭加工：tab_height {0} mm が素材上面に達します（そこでの切込みは {1} mm）",
    "profile: tabs[{}] must be an (x, y) pair in mm, got {}": "輪郭加工：tabs[{0}] は mm の (x, y) の組にしてください（指定値 {1}）",
    "profile: tabs[{}] has a coordinate that is not a number: {}": "輪郭加工：tabs[{0}] に数値でない座標があります：{1}",
    "profile: lead_radius {} mm: the {} lead does not fit in the waste beside a contour away from its tabs: make "
    "lead_radius smaller or lead none":
        "輪郭加工：lead_radius {0} mm：{1} のアプローチがタブから離れた捨て側に収まりません。lead_radius を小さくするか lead を none にしてください",
    "profile: the {} does not fit inside every contour of {} for its {} pass: give a smaller tool or a larger outline":
        "輪郭加工：{0} は {2} パスで {1} のすべての輪郭の内側に入りません。小さい工具か大きい輪郭にしてください",
    "profile: contours of {} lie closer together than the {} can pass between, or a hole of it is narrower ({} "
    "pass): give a smaller tool or move them apart":
        "輪郭加工：{0} の輪郭どうしが近すぎるか穴が狭すぎて {1} が通れません（{2} パス）。小さい工具にするか輪郭を離してください",
    "profile: tool: {}": "輪郭加工：工具：{0}",
    "profile: tool: a profile is cut with a flat end mill, not a {}": "輪郭加工：工具：輪郭加工はフラットエンドミルで行います（{0} は不可）",
    "profile: {} must be one of {}, got {}": "輪郭加工：{0} は {1} のいずれかにしてください（指定値 {2}）",
    "profile: {} must be a number, got {}": "輪郭加工：{0} は数値にしてください（指定値 {1}）",
    "profile: {} must be more than 0, got {}": "輪郭加工：{0} は 0 より大きくしてください（指定値 {1}）",
    "profile: {} must be 0 or more, got {}": "輪郭加工：{0} は 0 以上にしてください（指定値 {1}）",
    "profile: tab_width and tab_height make each tab {} mm long; {} of them do not fit on {} ({} mm round)":
        "輪郭加工：tab_width と tab_height ではタブ1つが {0} mm の長さになり、{1} 個は {2}（周長 {3} mm）に収まりません",
    "profile: {} tab(s) do not fit on {} ({} mm round) a tool radius off its corners: give fewer tabs or a smaller "
    "tab_width":
        "輪郭加工：{0} 個のタブが角から工具半径を離して {1}（周長 {2} mm）に収まりません。タブを減らすか tab_width を小さくしてください",
    "profile: {}: the tab ({} mm long with tab_width and tab_height) is longer than its contour ({} mm round)":
        "輪郭加工：{0}：タブ（tab_width と tab_height で {1} mm）が輪郭（周長 {2} mm）より長いです",
    "profile: {} sits within a tool radius of a corner: move it along the contour":
        "輪郭加工：{0} が角から工具半径以内にあります。輪郭に沿って移動してください",
    "profile: {} overlaps another tab: move them apart": "輪郭加工：{0} が別のタブと重なっています。離してください",
    "profile: a triangular tab tab_height {} mm high on tab_width {} mm has flanks steeper than {} degrees: make it at "
    "least {} mm wide":
        "輪郭加工：tab_height {0} mm、tab_width {1} mm の三角タブは斜面が {2} 度より急です。幅を {3} mm 以上にしてください",
    # warnings (Part.warnings)
    "profile {}: no tabs and cut through: the part comes loose on the last pass":
        "輪郭加工 {0}：タブがなく貫通します。最後のパスで部品が外れます",
    "profile {}: contour {} has no tabs and is cut through: its piece comes loose on the last pass":
        "輪郭加工 {0}：輪郭 {1} にタブがなく貫通します。その部分は最後のパスで外れます",
}

# Materials, feeds and speeds (issue 31): Machine & Stock's material, the check before export, batch.py feeds
FEEDS_TEXTS = {
    "Material": "材料",
    "What the stock is: each operation's spindle speed and feed are checked against its tool's chip-load band in "
    "it before export (None: not checked)":
        "素材の材質：書き出し前に各工程の主軸回転数と送りを、この材料での工具の1刃送り（チップロード）の範囲と照合します"
        "（なし：照合しない）",
    "None": "なし",
    "No material: the feeds are not checked": "材料なし：送りを照合しません",
    "Softwood": "針葉樹",
    "pine, spruce, cedar, Japanese cedar (sugi), cypress (hinoki)": "松、スプルース、シダー、杉、檜",
    "Hardwood": "広葉樹",
    "Japanese magnolia (hoonoki: the gouge-texture paper's name plate), oak, maple, walnut, cherry, beech":
        "朴（ホオノキ：彫刻刀跡の論文の表札）、オーク、メープル、ウォールナット、チェリー、ブナ",
    "MDF": "MDF（中質繊維板）",
    "medium-density fibreboard, particle board": "中質繊維板、パーティクルボード",
    "Plywood": "合板",
    "birch, lauan and softwood plywood": "バーチ合板、ラワン合板、針葉樹合板",
    "Acrylic": "アクリル",
    "cast acrylic (PMMA), polycarbonate: the chart's hard plastics": "キャストアクリル（PMMA）、ポリカーボネート：表の硬質樹脂",
    "HDPE": "HDPE（高密度ポリエチレン）",
    "HDPE, UHMW, polypropylene: the chart's soft plastics": "HDPE、超高分子量ポリエチレン、ポリプロピレン：表の軟質樹脂",
    "Aluminium": "アルミニウム",
    "6061 and similar wrought alloys": "A6061 などの展伸材",
    "Brass": "真鍮",
    "yellow brass, free-cutting brass, soft bronze": "黄銅、快削黄銅、軟質青銅",
}
FEEDS_NESTED = {"feeds: operation {} ({}) in {}: {}": (3,), "batch.py feeds --tool {}: {}": (1,), "batch.py feeds {} {}: {}": (2,),
                "job file {}: [setup] material: {}": (1,)}
FEEDS_TEMPLATES = {
    "feeds: operation {} ({}) in {}: {}": "送り：工程 {0}（{1}）、材料 {2}：{3}",
    "chip load {} mm per tooth is below the safe band {} - {} mm: the tool rubs (heat, burning, a dull edge); raise "
    "the feed or lower the spindle speed":
        "1刃送り {0} mm が安全範囲 {1}〜{2} mm を下回っています：工具がこすれます（発熱、焦げ、刃先の摩耗）。送りを上げるか"
        "主軸回転数を下げてください",
    "chip load {} mm per tooth is above the safe band {} - {} mm: the tool is overloaded (breakage risk); lower the "
    "feed or raise the spindle speed":
        "1刃送り {0} mm が安全範囲 {1}〜{2} mm を超えています：工具に過負荷（折損のおそれ）。送りを下げるか主軸回転数を"
        "上げてください",
    "spindle {} rpm is beyond the machine {}: {} - {} rpm": "主軸 {0} rpm は機械 {1} の範囲 {2}〜{3} rpm を超えています",
    "spindle {} rpm is below the machine {}: {} - {} rpm": "主軸 {0} rpm は機械 {1} の範囲 {2}〜{3} rpm を下回っています",
    "feed {} mm/min is beyond the machine {}: 0 - {} mm/min": "送り {0} mm/min は機械 {1} の範囲 0〜{2} mm/min を超えています",
    "batch.py feeds --tool {}: give KIND:DIAMETER or KIND:DIAMETER:FLUTES, e.g. flat:6:2":
        "batch.py feeds の --tool {0}：種類:直径 または 種類:直径:刃数 で指定してください（例 flat:6:2）",
    "batch.py feeds --tool {}: {}": "batch.py feeds の --tool {0}：{1}",
    "{} = {}: must be a number": "{0} = {1}：数値にしてください",
    "batch.py feeds {} {}: {}": "batch.py feeds のオプション {0} {1}：{2}",
    "job file {}: [setup] material: {}": "ジョブファイル {0}：[setup] material：{1}",
    "{} = {}: must be a positive number": "{0} = {1}：正の数にしてください",
    "unknown tool kind {}: the kinds are {}": "工具の種類 {0} は不明です（種類は {1}）",
    "flutes = {}: must be a whole number 1..{}": "刃数 = {0}：1〜{1} の整数にしてください",
    "unknown operation kind {}: the kinds are {}": "加工の種類 {0} は不明です（種類は {1}）",
    "unknown material {}: the materials are {}": "材料 {0} は不明です（材料は {1}）",
    "unknown tool material {}: the tool materials are {}": "工具材質 {0} は不明です（工具材質は {1}）",
}
PROPERTY_TEXTS.update(FEEDS_TEXTS)
MESSAGE_TEMPLATES.update(FEEDS_TEMPLATES)
NESTED.update(FEEDS_NESTED)
# drills fed per revolution; the single-workflow batch runs' --material (feeds follow-up)
DRILL_FEEDS_NESTED = {"--material {}: {}": (1,), "feed per revolution ({})": (0,),
                      "feed per revolution ({}); the chart's low end in a harder material": (0,)}
DRILL_FEEDS_TEMPLATES = {
    "feed per revolution {} mm per revolution is below the safe band {} - {} mm: the tool rubs (heat, burning, a "
    "dull edge); raise the feed or lower the spindle speed":
        "1回転あたりの送り {0} mm が安全範囲 {1}〜{2} mm を下回っています：工具がこすれます（発熱、焦げ、刃先の摩耗）。"
        "送りを上げるか主軸回転数を下げてください",
    "feed per revolution {} mm per revolution is above the safe band {} - {} mm: the tool is overloaded (breakage "
    "risk); lower the feed or raise the spindle speed":
        "1回転あたりの送り {0} mm が安全範囲 {1}〜{2} mm を超えています：工具に過負荷（折損のおそれ）。送りを下げるか"
        "主軸回転数を上げてください",
    "feed per revolution": "1回転あたりの送り",
    "feed per revolution ({})": "1回転あたりの送り（{0}）",
    "feed per revolution; the chart's low end in a harder material": "1回転あたりの送り。硬い材料なので表の下限",
    "feed per revolution ({}); the chart's low end in a harder material": "1回転あたりの送り（{0}）。硬い材料なので表の下限",
    "--material {}: {}": "オプション --material {0}：{1}",
    "T{}: {} rpm, feed {} mm/min, feed per revolution {} mm (band {} - {} mm)":
        "T{0}：{1} rpm、送り {2} mm/min、1回転あたりの送り {3} mm（範囲 {4}〜{5} mm）",
    "the chart's row up to {} mm": "表の {0} mm までの行",
    "above the chart's largest diameter ({} mm): its band used": "表の最大径（{0} mm）を超えるため、その範囲を使用",
}
MESSAGE_TEMPLATES.update(DRILL_FEEDS_TEMPLATES)
NESTED.update(DRILL_FEEDS_NESTED)
# the tool library (toolpath/tooling, operators/jobtools.py, operators/toolbatch.py)
TOOLLIB_OPERATORS = {
    "Load Tool Library": "工具ライブラリを読み込み", "Save Tool Library": "工具ライブラリを保存",
    "Add Library Tool": "ライブラリに工具を追加", "Remove Library Tool": "ライブラリから工具を削除",
    "Import Tools": "工具を読み込み", "Export Tools": "工具を書き出し",
    "Save": "保存", "Import": "読込", "Export": "書出",
    "Use for Roughing": "荒加工に使用", "Use for Finishing": "仕上げに使用", "Use for the Job": "この加工に使用",
    "Use for the Row": "選択した行に使用", "Use for Rest Machining": "残り削りに使用", "Use as the Drill": "ドリルとして使用",
    "Use for Helix Milling": "ヘリカル加工に使用", "Use for Spotting": "センタもみに使用", "Use for Clearing": "底の除去に使用",
    "Put it on the job list's selected row, not on the picked workflow's panel":
        "選んだワークフローのパネルではなく、ジョブリストで選択した行に設定します",
}
TOOLLIB_TEXTS = {
    "Add a 6 mm flat end mill under the next free number, and save":
        "空いている次の番号に 6 mm フラットエンドミルを追加して保存します",
    "Write the tool library to a file (Kezuri .toml, LinuxCNC .tbl, Fusion 360 .json, FreeCAD .fctl)":
        "工具ライブラリをファイルに書き出します（Kezuri .toml、LinuxCNC .tbl、Fusion 360 .json、FreeCAD .fctl）",
    "Merge a tool file (Kezuri .toml, LinuxCNC .tbl, Fusion 360 .json, FreeCAD .fctl) into the library":
        "工具ファイル（Kezuri .toml、LinuxCNC .tbl、Fusion 360 .json、FreeCAD .fctl）をライブラリに取り込みます",
    "FreeCAD (.fctl)": "FreeCAD 形式 (.fctl)", "A FreeCAD tool library and its tool bit files":
        "FreeCAD の工具ライブラリとその工具ビットファイル",
    "Read the tool library file (edits not saved are dropped)": "工具ライブラリのファイルを読み込みます（保存していない編集は破棄されます）",
    "Remove the selected tool from the library, and save": "選択した工具をライブラリから削除して保存します",
    "Check every row and write the tool library file (the file before is kept as a backup)":
        "すべての行を確認して工具ライブラリのファイルに書き込みます（以前のファイルはバックアップとして残ります）",
    "Format": "形式", "From Extension": "拡張子から",
    "The format the file name's extension says": "ファイル名の拡張子が示す形式",
    "A Fusion 360 tool library": "Fusion 360 の工具ライブラリ", "Fusion 360 (.json)": "Fusion 360 形式 (.json)",
    "Kezuri's own tool library file": "Kezuri 独自の工具ライブラリファイル", "Kezuri (.toml)": "Kezuri 形式 (.toml)",
    "A LinuxCNC tool table": "LinuxCNC のツールテーブル", "LinuxCNC (.tbl)": "LinuxCNC 形式 (.tbl)",
    "Table Units": "テーブルの単位", "A LinuxCNC tool table's units": "LinuxCNC ツールテーブルの単位",
    "A LinuxCNC tool table's units (the table does not say)": "LinuxCNC ツールテーブルの単位（テーブルには書かれていません）",
    "Millimetres": "ミリメートル", "Inches": "インチ",
    "The tool table is in millimetres": "ツールテーブルはミリメートル単位です",
    "The tool table is in inches": "ツールテーブルはインチ単位です",
    "Replace Same Numbers": "同じ番号を置き換え",
    "Tools of the file replace the library's tools of the same number": "ファイルの工具で同じ番号のライブラリ工具を置き換えます",
    "V-bit or engraver: included angle; drill: point angle (degrees)":
        "Vビット・彫刻刃：刃先角、ドリル：先端角（度）",
    "Angle": "角度", "Bull nose corner radius (mm)": "ラジアスエンドミルのコーナー半径 (mm)",
    "Number of flutes": "刃の数", "Flutes": "刃数",
    "The holder's (collet nut's) diameter (mm); 0: not known": "ホルダー（コレットナット）の直径 (mm)。0：不明",
    "Holder Diameter": "ホルダー径", "Pointed engraving cutter": "先の尖った彫刻刃", "Engraver": "彫刻刃",
    "Material": "材質", "Solid carbide": "超硬ソリッド", "Carbide": "超硬", "High-speed steel": "ハイス鋼", "HSS": "ハイス",
    "Tool number, the T word": "工具番号（T ワード）", "The maker's product number": "メーカーの品番", "Product ID": "品番",
    "How far the tool stands out of the holder (mm); 0: not measured": "ホルダーからの工具の突き出し (mm)。0：未測定",
    "Stick-Out": "突き出し", "Who makes the tool": "工具のメーカー", "Vendor": "メーカー",
    "Select a tool in the library first": "先にライブラリの工具を選択してください",
    "The library file cannot be read": "ライブラリのファイルを読み込めません",
    "Put the selected library tool on the picked job (its number, diameter and flute length)":
        "選択したライブラリの工具を選んだ加工に設定します（番号・直径・刃長）",
    "a FreeCAD library is several files: export it to a .fctl path":
        "FreeCAD のライブラリは複数のファイルです。.fctl のパスに書き出してください",
}
TOOLLIB_NESTED = {"{}: refused: {}": (1,), "T{}: not a tool a program can use: {}": (1,),
                  "{}: {} = {} cannot be used: {}": (3,), "the tool library cannot be read, and is left as it is: {}{}": (0,)}
TOOLLIB_TEMPLATES = {
    # notes of an import (reported as warnings)
    "{}: only the number and diameter are in the table: taken as a {} from the comment (angle {}); flutes, lengths "
    "and material at their defaults":
        "{0}：テーブルには番号と直径しかありません。コメントから {1}（角度 {2}）とし、刃数・長さ・材質は既定値です",
    "{}: a {} is not a tool Kezuri cuts with: left out": "{0}：{1} は Kezuri が使う工具ではないため除きました",
    "{}: a {} bit is not a tool Kezuri cuts with: left out": "{0}：{1} のビットは Kezuri が使う工具ではないため除きました",
    "{}: its flat tip (FlatRadius {} mm) is not kept: Kezuri's V-bit comes to a point":
        "{0}：先端の平坦部（FlatRadius {1} mm）は保持しません。Kezuri の Vビットは先端が尖っています",
    "{}: a FreeCAD library is read with its bit files: read it from its path":
        "{0}：FreeCAD のライブラリは工具ビットファイルと一緒に読みます。そのパスから読み込んでください",
    "{}: parameter CuttingEdgeAngle is missing (a V-bit's included angle)":
        "{0}：パラメーター CuttingEdgeAngle（Vビットの刃先角）がありません",
    "{}: attribute Material = {} is not one of {}": "{0}：属性 Material = {1} は {2} のいずれでもありません",
    "{}: attribute {} is not Kezuri's JSON": "{0}：属性 {1} が Kezuri の JSON ではありません",
    "{}: attribute {} has an unknown field {}": "{0}：属性 {1} に不明な項目 {2} があります",
    "{}: not a FreeCAD tool library: no \"tools\" list": "{0}：FreeCAD の工具ライブラリではありません：\"tools\" リストがありません",
    "{}: needs \"nr\" (the tool number) and \"path\" (its bit file)":
        "{0}：\"nr\"（工具番号）と \"path\"（工具ビットファイル）が必要です",
    "{}: parameter {} = {} is not a quantity (\"6.0 mm\")": "{0}：パラメーター {1} = {2} は量（\"6.0 mm\"）ではありません",
    "{}: parameter {} = {}: unit {} is not one of {}": "{0}：パラメーター {1} = {2}：単位 {3} は {4} のいずれでもありません",
    "{}: parameter {} = {} is not a finite number": "{0}：パラメーター {1} = {2} は有限の数ではありません",
    "{}: not a FreeCAD {}: not JSON ({} at line {}, column {})":
        "{0}：FreeCAD の {1} ではありません：JSON ではありません（{3} 行 {4} 列：{2}）",
    "{}: the bit file {} is not there (looked for {})": "{0}：工具ビットファイル {1} がありません（探した場所 {2}）",
    "{}: not a FreeCAD tool bit (parameter and attribute must be objects)":
        "{0}：FreeCAD の工具ビットではありません（parameter と attribute はオブジェクトにしてください）",
    "{}: parameter Diameter is missing": "{0}：パラメーター Diameter がありません",
    "{}: parameter FlatRadius is missing (a bull nose's flat)": "{0}：パラメーター FlatRadius（ラジアスエンドミルの平らな底）がありません",
    "Tool library: {} tools from {}": "工具ライブラリ：{1} から {0} 本の工具",
    "Saved the tool library to {}": "工具ライブラリを {0} に保存しました",
    "Imported {} new and {} replaced tools from {}": "{2} から新規 {0} 本、置き換え {1} 本の工具を取り込みました",
    "Exported {} tools to {}": "{0} 本の工具を {1} に書き出しました",
    "{}: a {} operation does not take its tools from the library; the kinds that do are {}":
        "{0}：{1} の加工は工具ライブラリから工具を取りません（取る種類は {2}）",
    "{}: give tool or tools, not both": "{0}：tool と tools はどちらか一方を指定してください",
    "{}: tools must be a table of slot = tool number, e.g. tools = {{ {} = 3 }}":
        "{0}：tools は「スロット = 工具番号」の表にしてください（例 tools = {{ {1} = 3 }}）",
    "{}: tools.{} is not a tool of a {}; its tools are {}": "{0}：tools.{1} は {2} の工具ではありません（工具は {3}）",
    "{}: {} = {} cannot be used: {}": "{0}：{1} = {2} は使えません：{3}",
    "{}: {} = {} is {}; the {}'s {} tool must be a {}": "{0}：{1} = {2} は {3} です。{4} の {5} 工具は {6} にしてください",
    "{}: {} = {} is {} with a {}° point; the {} is planned for a {}° one (a program's tool does not carry its angle "
    "yet)":
        "{0}：{1} = {2} は先端角 {4}° の {3} です。{5} は {6}° の工具で計画されます（プログラムの工具はまだ角度を持ちません）",
    "{}: settings.{} and {} = {} both give the {} tool; give one":
        "{0}：settings.{1} と {2} = {3} の両方が {4} 工具を指定しています。どちらか一方にしてください",
    "{} is the tool library itself (or its backup); export to another file":
        "{0} は工具ライブラリそのもの（またはそのバックアップ）です。別のファイルに書き出してください",
    "tool library format {} is not one of {}": "工具ライブラリの形式 {0} は {1} のいずれでもありません",
    "{}: which tool library format is {}? Known: {}; or name the format":
        "{0}：{1} はどの工具ライブラリ形式ですか？既知の形式：{2}。または形式を指定してください",
    "{}: units are given by the {} file itself; --units is for tool tables":
        "{0}：単位は {1} ファイル自身が示します。--units はツールテーブル用です",
    "a {} file is written in mm; units are for tool tables": "{0} ファイルは mm で書き出します。単位の指定はツールテーブル用です",
    "{}: {} bytes is not a tool library (at most {})": "{0}：{1} バイトは工具ライブラリではありません（最大 {2}）",
    "{}: a folder, not a tool library file": "{0}：フォルダーです。工具ライブラリのファイルではありません",
    "{}: cannot be read ({})": "{0}：読み込めません（{1}）",
    "{}: line {}: not UTF-8 text": "{0}：{1} 行目：UTF-8 のテキストではありません",
    "{}: BMC = {} is not one of {}": "{0}：BMC = {1} は {2} のいずれでもありません",
    "{}: not a Fusion 360 tool library: not JSON ({} at line {}, column {})":
        "{0}：Fusion 360 の工具ライブラリではありません：JSON ではありません（{2} 行 {3} 列：{1}）",
    "{}: not a Fusion 360 tool library: no \"data\" list of tools":
        "{0}：Fusion 360 の工具ライブラリではありません：工具の \"data\" リストがありません",
    "{}: not an object": "{0}：オブジェクトではありません",
    "{}: {} = {} is not a number": "{0}：{1} = {2} は数値ではありません",
    "{}: {} = {} is not text": "{0}：{1} = {2} は文字列ではありません",
    "{}: post-process and geometry must be objects": "{0}：post-process と geometry はオブジェクトにしてください",
    "{}: post-process.number (the tool number) is missing": "{0}：post-process.number（工具番号）がありません",
    "{}: unit = {} is not one of {}": "{0}：unit = {1} は {2} のいずれでもありません",
    "{}: geometry NOF = {} is not a whole number of flutes": "{0}：geometry NOF = {1} は刃数として整数ではありません",
    "{}: not a Kezuri tool library: not TOML ({})": "{0}：Kezuri の工具ライブラリではありません：TOML ではありません（{1}）",
    "{}: unknown key {}; the file has {}": "{0}：不明なキー {1}（ファイルのキーは {2}）",
    "{}: format = {}, not {}: not a Kezuri tool library": "{0}：format = {1} で {2} ではありません：Kezuri の工具ライブラリではありません",
    "{}: version = {}; this Kezuri reads version {} (a newer Kezuri wrote it?)":
        "{0}：version = {1}。この Kezuri が読めるのはバージョン {2} です（新しい Kezuri で書かれましたか？）",
    "{}: units = {}; a Kezuri tool library is in \"mm\"": "{0}：units = {1}。Kezuri の工具ライブラリは \"mm\" です",
    "{}: tools must be [[tools]] tables": "{0}：tools は [[tools]] の表にしてください",
    "{}: not a table": "{0}：表ではありません",
    "{}: {} = {} is not a single value": "{0}：{1} = {2} は単一の値ではありません",
    "{}: flutes {} is not a whole number 1..{}": "{0}：刃数 {1} は 1..{2} の整数ではありません",
    "{}: material {} is not one of {}": "{0}：材質 {1} は {2} のいずれでもありません",
    "{}: {} {} is not text": "{0}：{1} {2} は文字列ではありません",
    "{}: a {} has no tip angle (got {})": "{0}：{1} に先端角はありません（指定値 {2}）",
    "{}: a {} needs its included angle (degrees)": "{0}：{1} には先端角（度）が必要です",
    "{}: angle {} is not an included angle 1..179 degrees": "{0}：角度 {1} は 1..179 度の先端角ではありません",
    "T{}: not a tool a program can use: {}": "T{0}：プログラムで使える工具ではありません：{1}",
    "{}: unknown field {}; the fields are {}": "{0}：不明な項目 {1}（項目は {2}）",
    "{}: the field {} is missing": "{0}：項目 {1} がありません",
    "{}: refused: {}": "{0}：受け付けません：{1}",
    "{}: not a tool": "{0}：工具ではありません",
    "tool number T{} is given twice: {} ({}) and {} ({})": "工具番号 T{0} が2回あります：{1}（{2}）と {3}（{4}）",
    "no tool T{} in the tool library (it has {})": "工具ライブラリに T{0} はありません（あるのは {1}）",
    "T{} is already in the library ({}); refused: {}": "T{0} はすでにライブラリにあります（{1}）。受け付けません：{2}",
    "{} tool number(s) already in the library: {}; nothing was imported (replace them to overwrite)":
        "{0} 個の工具番号がすでにライブラリにあります：{1}。何も取り込んでいません（上書きするには置き換えを指定してください）",
    "tool {} is not a tool number (3 or \"T3\")": "tool {0} は工具番号（3 または \"T3\"）ではありません",
    "tool number {} is not a whole number 1..{}": "工具番号 {0} は 1..{1} の整数ではありません",
    "{}: {} {} is not a number (mm)": "{0}：{1} {2} は数値（mm）ではありません",
    "{}: {} {} must be positive (mm)": "{0}：{1} {2} は正の値（mm）にしてください",
    "{}: a ball end mill's corner radius is its radius {} mm, not {}":
        "{0}：ボールエンドミルのコーナー半径は工具半径 {1} mm です（{2} ではありません）",
    "{}: corner_radius {} mm must be above 0 and at most the radius {} mm":
        "{0}：corner_radius {1} mm は 0 より大きく工具半径 {2} mm 以下にしてください",
    "{}: a {} has no corner radius (got {} mm)": "{0}：{1} にコーナー半径はありません（指定値 {2} mm）",
    "{}: no D word: the tool's diameter is missing": "{0}：D ワードがありません：工具径がありません",
    "{}: the comment's {}{{...}} repeats number or diameter (the T and D words give them)":
        "{0}：コメントの {1}{{...}} が番号か径を繰り返しています（T と D ワードで指定されます）",
    "{}: the comment's {}{{...}} has an unknown field {}": "{0}：コメントの {1}{{...}} に不明な項目 {2} があります",
    "T{}: its name {} cannot stand in a tool table's comment (line breaks, spaces at the ends or in runs, or "
    "'kezuri{{'): rename it first":
        "T{0}：名前 {1} はツールテーブルのコメントに入りません（改行、前後や連続の空白、'kezuri{{'）。先に名前を変えてください",
    "tool table units {} are not one of {}": "ツールテーブルの単位 {0} は {1} のいずれでもありません",
    "{}: {} is not a tool table word (T P X Y Z A B C U V W D I J Q)":
        "{0}：{1} はツールテーブルのワード（T P X Y Z A B C U V W D I J Q）ではありません",
    "{}: {} is given twice": "{0}：{1} が2回指定されています",
    "{}: {}: {} is not a number": "{0}：{1}：{2} は数値ではありません",
    "{}: {} is not a finite number": "{0}：{1} は有限の数ではありません",
    "{}: {}: {} must be a whole number": "{0}：{1}：{2} は整数にしてください",
    "{}: the comment's {}{{...}} is not JSON ({} at column {} of the comment)":
        "{0}：コメントの {1}{{...}} が JSON ではありません（コメントの {3} 列目：{2}）",
    "{}: the comment's {}{{...}} is not a table of fields": "{0}：コメントの {1}{{...}} は項目の表ではありません",
    "{}: no T word (tool number)": "{0}：T ワード（工具番号）がありません",
    "{}: cannot be written ({})": "{0}：書き込めません（{1}）",
    "the tool library cannot be read, and is left as it is: {}{}": "工具ライブラリを読み込めないため、そのままにしています：{0}{1}",
    "{}: the library would not read back as it is; nothing was written":
        "{0}：ライブラリが同じ内容で読み戻せないため、何も書き込んでいません",
    "{}: the tool library cannot be written ({}); the file is as it was":
        "{0}：工具ライブラリを書き込めません（{1}）。ファイルは元のままです",
}

# work estimates before planning (toolpath/workload.py, issue 27): the message is
# "<what> is about <n> <quantity>, over the <limit> this machine can plan; <advice>", each part
# translated by its own template (NESTED)
WORKLOAD_NESTED = {"{} is about {} {}, over the {} this machine can plan; {}": (0, 2, 4), "operation {}: {}": (1,),
                   "{} is about {} {}, over the {} this machine can simulate; {}": (0, 2, 4),
                   "workingstep #{} '{}': {}": (2,), "setup #{} of workplan #{} left out: {}": (2,),
                   "the bounding geometry of workpiece #{} is left out: {}": (1,)}
WORKLOAD_TEMPLATES = {
    "{} is about {} {}, over the {} this machine can plan; {}":
        "{0} は約 {1} {2} で、この機械で計画できる上限 {3} を超えています。{4}",
    "{} is about {} {}, over the {} this machine can simulate; {}":
        "{0} は約 {1} {2} で、この機械でシミュレーションできる上限 {3} を超えています。{4}",
    # what is estimated
    "carve {}: the finishing raster at scallop {} mm and sample spacing {} mm":
        "曲面加工 {0}：スカラップ {1} mm、サンプル間隔 {2} mm の仕上げラスタ",
    "carve {}: the roughing through {} mm of stock above the design at step down {} mm ({} levels)":
        "曲面加工 {0}：形状の上の素材 {1} mm を切込み深さ {2} mm で削る荒加工（{3} 段）",
    "engrave {}: the gouge texture at stepover {} mm and spacing {} mm over {} mm2":
        "彫刻 {0}：ステップオーバー {1} mm、間隔 {2} mm、面積 {3} mm2 の彫刻刀跡テクスチャ",
    "engrave {}: the band finishing at band stepover {} mm and band step down {} mm ({} rings, {} levels round {} "
    "mm of letter outlines)":
        "彫刻 {0}：帯のステップオーバー {1} mm、帯の切込み深さ {2} mm の帯仕上げ（文字の輪郭 {5} mm を {3} 周、{4} 段）",
    "pocket {}: {} mm2 at stepover {} mm and step down {} mm ({} levels)":
        "ポケット {0}：{1} mm2 をステップオーバー {2} mm、切込み深さ {3} mm で（{4} 段）",
    "profile {}: {} mm of outline at step down {} mm ({} levels)":
        "輪郭加工 {0}：輪郭 {1} mm を切込み深さ {2} mm で（{3} 段）",
    "chamfer {}: the drawing": "面取り {0}：図面",
    "drill {}: the drawing's holes": "穴あけ {0}：図面の穴",
    "drill {}: the shortest order of its holes": "穴あけ {0}：穴の最短順序",
    "drill {}: {} holes {} mm deep at peck {} mm": "穴あけ {0}：深さ {2} mm の穴 {1} 個をペック {3} mm で",
    "pocket {}: the toolpath at a spacing of {} mm and a step down of {} mm":
        "ポケット {0}：点間隔 {1} mm、切込み深さ {2} mm の工具経路",
    "the STEP-NC file {}": "STEP-NC ファイル {0}",
    "the NC file {}": "NC ファイル {0}",
    "project #{}: its name is {} characters; the first {} are used, followed by ...":
        "プロジェクト #{0}：名前が {1} 文字あります。先頭の {2} 文字に ... を付けて使います",
    "no workpiece BLOCK: the stock bottom is taken as Z {}, the depth of the deepest through feature #{} '{}' ({} mm "
    "below its top); check the stock's thickness, or give the workpiece its BLOCK":
        "ワークピースに BLOCK がありません：素材の底を、最も深い貫通フィーチャ #{1} '{2}' の深さ Z {0}（上面から {3} mm）と"
        "しました。素材の厚さを確認するか、ワークピースに BLOCK を指定してください",
    "through feature #{} '{}' ends at Z {}, {} mm above that stock bottom: it does not go through":
        "貫通フィーチャ #{0} '{1}' は Z {2} で終わり、その素材の底より {3} mm 上です：貫通しません",
    # warnings and notes the panel reports (tests/test_translations.py: every formatted warning)
    "{}the part falls free: its micro-joints leave no web": "{0}部品が抜け落ちます：マイクロジョイントが残りません",
    "{}: the tool is too big to enter a gap of {} mm^2 in {} of letters {} near X{} Y{}; it is left uncut":
        "{0}：文字 {3} の {2} にある {1} mm^2 のすき間（X{4} Y{5} 付近）は工具が大きすぎて入れません。削り残します",
    "{}: the tool is too big to enter a gap of {} mm^2 in letters {} near X{} Y{}; it is left uncut":
        "{0}：文字 {2} の {1} mm^2 のすき間（X{3} Y{4} 付近）は工具が大きすぎて入れません。削り残します",
    "no room for a {} mm helix at X{} Y{}; ramped instead":
        "X{1} Y{2} に {0} mm のヘリカルの余地がありません。代わりにランプで入ります",
    "#{} {} in workplan #{} skipped: only workingsteps and workplans are supported":
        "ワークプラン #{2} の #{0} {1} を飛ばしました：対応しているのはワーキングステップとワークプランだけです",
    "setup #{} of workplan #{} left out: {}": "ワークプラン #{1} のセットアップ #{0} を省きました：{2}",
    "the bounding geometry of workpiece #{} is left out: {}": "ワークピース #{0} の外形を省きました：{1}",
    "workingstep #{} '{}' skipped: switched off (left out of the order to cut)":
        "ワーキングステップ #{0} '{1}' を飛ばしました：オフ（加工順から外しています）",
    "workingstep #{} '{}' assumes roughing #{} '{}' was done before it":
        "ワーキングステップ #{0} '{1}' は、荒加工 #{2} '{3}' が先に済んでいる前提です",
    "the floor fillet R{} is cut with the tool's corner radius R{}": "底のフィレット R{0} を工具のコーナ半径 R{1} で削ります",
    "hole #{}: helical entry at the file's {} degrees (pitch = pi x circle diameter x tan {}: {} mm a turn on the {} mm "
    "circle)": "穴 #{0}：ファイルの {1} 度でヘリカル進入（ピッチ = π × 円の直径 × tan {2}：直径 {4} mm の円で1周 {3} mm）",
    "hole #{}: the {} mm circle is too small for a {} degree helix (more than {} turns a layer): one turn per layer "
    "there": "穴 #{0}：直径 {1} mm の円は {2} 度のヘリカルには小さすぎます（1段 {3} 周を超える）：そこでは1段1周にします",
    "through hole: the drill goes {} mm below the hole bottom ({}) to Z {}":
        "貫通穴：ドリルは穴底より {0} mm 下（{1}）の Z {2} まで進みます",
    "no dwell of {} s at the bottom (not written)": "穴底での {0} 秒のドウェルはありません（出力しません）",
    "hole {} at {} lies beyond the {} mm any machine reaches (a unit mistake?)":
        "穴 {0}（{1}）は、どの機械も届かない {2} mm より遠くにあります（単位の間違い？）",
    "turn-mill {}: {} faces at sample spacing {} mm": "複合加工 {0}：{1} 面をサンプル間隔 {2} mm で",
    # what is counted
    "tool positions": "工具位置", "moves": "移動", "gouges": "彫刻刀跡",
    "mm of path": "mm の経路", "outline points": "輪郭点", "holes": "穴", "holes to order": "順序付けする穴",
    "pecks": "ペック", "path points": "経路点", "bytes": "バイト", "classification samples": "分類サンプル",
    "lines": "行",
    # what to do
    "raise sample spacing to {} mm or more, or the scallop":
        "サンプル間隔を {0} mm 以上にするか、スカラップを大きくしてください",
    "raise step down to {} mm or more, or give less stock above the design":
        "切込み深さを {0} mm 以上にするか、形状の上の素材を減らしてください",
    "raise stepover to {} mm or more": "ステップオーバーを {0} mm 以上にしてください",
    "raise band stepover or band step down": "帯のステップオーバーか帯の切込み深さを大きくしてください",
    "raise stepover to {} mm or more, or the step down":
        "ステップオーバーを {0} mm 以上にするか、切込み深さを大きくしてください",
    "raise step down to {} mm or more": "切込み深さを {0} mm 以上にしてください",
    "simplify the drawing (fewer points)": "図面を単純にしてください（点を減らす）",
    "split the holes into several operations": "穴を複数の工程に分けてください",
    "set the order to 'given' (the drawing's), or split the holes into several operations":
        "順序を 'given'（図面の順）にするか、穴を複数の工程に分けてください",
    "raise peck to {} mm or more": "ペックを {0} mm 以上にしてください",
    "raise spacing to {} mm or more": "点間隔を {0} mm 以上にしてください",
    "raise the scallop": "スカラップを大きくしてください",
    "use a mesh of at most {} faces (each face is sampled at least 4 times)":
        "面が {0} 以下のメッシュを使ってください（各面を少なくとも 4 回サンプリングします）",
    "split it into files of fewer lines, or write it with a coarser stepover or tolerance":
        "行数の少ない複数のファイルに分けるか、ステップオーバーか公差を粗くして書き出してください",
    "a workplan is a few MB: check that this is the file meant":
        "ワークプランは数 MB です。意図したファイルか確認してください",
    "raise sample spacing to {} mm or more, or use a mesh of fewer faces":
        "サンプル間隔を {0} mm 以上にするか、面の少ないメッシュを使ってください",
}

MESSAGE_TEMPLATES.update(JOBLIST_TEMPLATES)
MESSAGE_TEMPLATES.update(PROFILE_TEMPLATES)
MESSAGES.update(PROFILE_TEXTS)
MESSAGE_TEMPLATES.update(POCKET_TEMPLATES)
# the router kinds' panels and chamfered holes (issue 29)
ROUTER_TEMPLATES = {
    "{}: settings.{} = {}: {}": "{0}：settings.{1} = {2} は設定できません：{3}",
    '{}: no shape and no plate: give objects = {{ shape = "..." }} (a closed curve, Text or mesh), or pick the plate '
    'to cut out its outline':
        '{0}：形状も素材もありません。objects = {{ shape = "..." }}（閉じたカーブ、テキスト、メッシュ）を指定するか、'
        '素材を選んでその輪郭を切り抜いてください',
    '{}: outline = {}: the only outline a profile takes by name is "plate" (the plate\'s own); give other shapes as '
    'objects.shape':
        '{0}：outline = {1}：輪郭加工が名前で受け付ける輪郭は "plate"（素材自身の輪郭）だけです。ほかの形状は objects.shape で'
        '指定してください',
    "{}: objects.{}: a chamfer takes objects.edges (a curve, Text or mesh) and objects.holes (a curve or mesh with "
    "round holes)":
        "{0}：objects.{1}：面取りは objects.edges（カーブ、テキスト、メッシュ）と objects.holes（丸穴のあるカーブかメッシュ）を取ります",
    "{}: give the holes as holes = [[x, y, diameter], ...] or as objects.holes, not both":
        "{0}：穴は holes = [[x, y, 直径], ...] か objects.holes のどちらか一方で指定してください",
    '{}: no edges: give objects = {{ edges = "<curve, Text or mesh>" }} or holes = [[x, y, diameter], ...]':
        '{0}：エッジがありません。objects = {{ edges = "<カーブ、テキスト、メッシュ>" }} か holes = [[x, y, 直径], ...] を指定してください',
    "{}: holes must be a list of [x, y, diameter] in work mm": "{0}：holes はワーク座標 mm の [x, y, 直径] のリストにしてください",
    "chamfer: holes[{}] = {} is not [x, y, diameter] in mm": "面取り：holes[{0}] = {1} は mm の [x, y, 直径] ではありません",
    "chamfer: holes[{}]: the diameter must be more than 0 mm, got {}":
        "面取り：holes[{0}]：直径は 0 mm より大きくしてください（指定値 {1}）",
    "chamfer: {} is {} mm: with the tip {} mm below the chamfer the V-bit's axis would run {} mm in from its edge, "
    "past the centre; make tip_gap smaller":
        "面取り：{0} は {1} mm です。先端を面取りの {2} mm 下にすると V ビットの軸がエッジから {3} mm 内側、中心を越えて"
        "通ります。tip_gap を小さくしてください",
    "chamfer: {} is {} mm, narrower than the {} mm chamfer's V-bit ({} mm across the hole at the top): it would cut "
    "the far side":
        "面取り：{0} は {1} mm で、{2} mm の面取りの V ビット（上面で穴を横切る幅 {3} mm）より狭く、反対側を削ります",
    "#{} {}: {} {} is above 1: it is a ratio of the programmed value (0.5 for half), not a percentage; write {} for {} %":
        "#{0} {1}：{2} {3} が 1 を超えています。指令値に対する比（半分なら 0.5）で、百分率ではありません。{5} % なら {4} と書いてください",
    "an ISO 14649 ratio must be above 0 and at most 1, got {} (the reader checks it)":
        "ISO 14649 の比は 0 より大きく 1 以下にしてください（指定値 {0}、リーダーが確認します）",
    '{}: give objects.shape or outline = "plate", not both': '{0}：objects.shape か outline = "plate" のどちらか一方を指定してください',
}
MESSAGE_TEMPLATES.update(ROUTER_TEMPLATES)
NESTED.update(POCKET_NESTED)
# text too fine for the band finishing tool (issue 30: toolpath/engines/finetext.py, operators/engrave.py)
FINE_TEXT_TEMPLATES = {
    "the band finishing's {} mm tool is too big for {} of letters {}: {} mm^2 between its strokes is left uncut "
    "(gaps {} mm wide); make it at least {} mm tall (now {} mm)":
        "帯仕上げの {0} mm 工具は文字 {2} の {1} には太すぎます：線の間の {3} mm² が削り残ります"
        "（隙間の幅 {4} mm）。高さを {5} mm 以上にしてください（現在 {6} mm）",
    "the band finishing's {} mm tool is too big for {} of letters {}: {} mm^2 between its strokes is left uncut; "
    "no text up to {} times as tall lets the tool in: use a smaller tool":
        "帯仕上げの {0} mm 工具は文字 {2} の {1} には太すぎます：線の間の {3} mm² が削り残ります。"
        "{4} 倍の高さまで大きくしても工具が入りません。小さい工具を使ってください",
    "{}: too fine, needs {} mm": "{0}：細かすぎ、{1} mm 以上に",
    "{}: too fine at any size": "{0}：どの大きさでも細かすぎ",
    "and {} more too fine": "ほか {0} 文字も細かすぎ",
    "tool diameter must be a positive number of mm, got {}": "工具径は正の mm 数値で指定してください（指定値 {0}）",
}
MESSAGE_TEMPLATES.update(FINE_TEXT_TEMPLATES)

# V-carving (issue 30)
VCARVE_NESTED = {"{}: the V-carve: {}": (1,), "{}: the tools: {}": (1,), "the V-bit: {}": (0,)}
VCARVE_TEMPLATES = {
    "{}: the V-carve: {}": "{0}：V 彫り：{1}",
    "{}: the tools: {}": "{0}：工具：{1}",
    "the V-bit: {}": "V ビット：{0}",
    "{}: text.body has {} characters, more than {}": "{0}：text.body が {1} 文字あり、{2} 文字を超えています",
    "{}: text.size = {} must be a number of mm from {} to {}": "{0}：text.size = {1} は {2}〜{3} mm の数値にしてください",
    "{}: text.at = {} must be [x, y] in work mm": "{0}：text.at = {1} はワーク座標 mm の [x, y] にしてください",
    "{}: text.font = {} is not a file name": "{0}：text.font = {1} はファイル名ではありません",
    "{}: text.font = {}: Blender cannot read it ({})": "{0}：text.font = {1}：Blender が読めません（{2}）",
    "{}: text {} has no glyph outlines in its font (is the font missing these characters?)":
        "{0}：テキスト {1} のフォントに字形の輪郭がありません（フォントにこの文字がないのでは？）",
    "{}: objects.{}: a V-carve's objects are {}": "{0}：objects.{1}：V 彫りのオブジェクトは {2} です",
    '{}: give the region as objects = {{ region = "<curve, Text or mesh>" }} or as text = "...", one of them':
        '{0}：領域は objects = {{ region = "<カーブ、テキストまたはメッシュ>" }} か text = "..." のどちらか一方で指定してください',
    "{}: settings.{} is not a V-carve setting; they are {}": "{0}：settings.{1} は V 彫りの設定ではありません（設定は {2}）",
    "{}: text.font = {}: no such font file (beside the job file, or among Blender's fonts)":
        "{0}：text.font = {1}：そのフォントファイルがありません（ジョブファイルの隣にも Blender のフォントにも）",
    "{}: text = {} is neither a string nor a table": "{0}：text = {1} は文字列でも表でもありません",
    "{}: text.{} is not a text key; they are {}": "{0}：text.{1} はテキストのキーではありません（キーは {2}）",
    "{}: text.body = {}: give the text to carve": "{0}：text.body = {1}：彫る文字を指定してください",
    "a tip angle ({} deg) is for a pointed tool, not a {}": "先端角（{0} 度）は先のとがった工具のもので、{1} には使えません",
    "tip angle must be from 1 to 179 degrees, got {}": "先端角は 1〜179 度にしてください（{0}）",
    "{}: V-carving needs pyvoronoi (Boost.Polygon's Voronoi), which is not installed for this Blender (no wheel for "
    "this platform)":
        "{0}：V 彫りには pyvoronoi（Boost.Polygon のボロノイ図）が必要ですが、この Blender には入っていません"
        "（このプラットフォーム用の wheel がありません）",
    "{}: the region has no medial axis (no area?)": "{0}：領域に中心軸がありません（面積がないのでは？）",
    "{}: no part of the medial axis lies inside the region": "{0}：中心軸のどの部分も領域の内側にありません",
    "{}: the outline reaches beyond {} m from the origin": "{0}：輪郭が原点から {1} m より遠くまで届いています",
    "{}: the region has no outline": "{0}：領域に輪郭がありません",
    "{}: the outline has {} segments, more than {}": "{0}：輪郭の線分が {1} 本あり、{2} 本を超えています",
    "{}: clear_stepover must be 0 (the end mill's radius) or more, got {}":
        "{0}：clear_stepover は 0（エンドミルの半径）以上にしてください（{1}）",
    "{}: tolerance must be from {} to {} mm, got {}": "{0}：tolerance は {1}〜{2} mm にしてください（{3}）",
    "{}: inlay must be one of {}, got {}": "{0}：inlay は {1} のいずれかにしてください（{2}）",
    "{}: max_depth {} mm (the plug's height) must be more than start_depth + glue_gap / sin(half angle) = {} mm":
        "{0}：max_depth {1} mm（プラグの高さ）は start_depth + glue_gap / sin(半角) = {2} mm より大きくしてください",
    "{}: max_depth {} mm (the pocket's flat bottom) must be more than start_depth {} mm, or the plug bottoms out on it":
        "{0}：max_depth {1} mm（ポケットの平らな底）は start_depth {2} mm より深くしてください。"
        "浅いとプラグが底に当たります",
    "{}: max_depth {} mm must be more than start_depth {} mm": "{0}：max_depth {1} mm は start_depth {2} mm より深くしてください",
    "{}: a male plug needs max_depth (how far the waste round it is cleared: the plug's height, more than start_depth "
    "{} mm)":
        "{0}：雄型プラグには max_depth（周りの捨て部分を削る深さ＝プラグの高さ、start_depth {1} mm より大きい値）が必要です",
    "{}: max_depth {} mm is deeper than the {}'s {} mm flutes": "{0}：max_depth {1} mm は {2} の刃長 {3} mm より深いです",
    "{}: at max_depth {} mm the {}'s cone is {} mm wide, more than its diameter: max_depth can be {} mm at most":
        "{0}：max_depth {1} mm では {2} の円錐の幅が {3} mm になり、直径を超えます。max_depth は最大 {4} mm です",
    "{}: the region is {} mm wide at X{} Y{}, wider than the {} can carve to a point ({} mm): set max_depth (at most "
    "{} mm) with a clear_tool for the flat inside":
        "{0}：領域の幅が X{2} Y{3} で {1} mm あり、{4} が先端まで彫れる幅（{5} mm）を超えています。"
        "max_depth（最大 {6} mm）と内側の平らな部分を削る clear_tool を指定してください",
    "{}: at max_depth {} mm a flat floor of {} mm^2 is left: give a clear_tool (a flat end mill) to clear it":
        "{0}：max_depth {1} mm では {2} mm^2 の平らな底が残ります。削るための clear_tool（平エンドミル）を指定してください",
    "{}: tool must be a V-bit, not a {}": "{0}：tool は V ビットにしてください（{1} ではなく）",
    "{}: clear_tool must be a flat end mill": "{0}：clear_tool は平エンドミルにしてください",
}
MESSAGE_TEMPLATES.update(VCARVE_TEMPLATES)
NESTED.update(VCARVE_NESTED)
# the V-carve's settings panels in the job list (issue 30: operators/vcarve.py settings_group)
VCARVE_PANEL_TEXTS = {
    "V-carve": "V 彫り", "V-carve closed regions and text with a V-bit; inlays":
        "閉じた領域と文字を V ビットで V 彫り、インレイ",
    "Inlay": "インレイ", "Max Depth": "最大深さ", "Start Depth": "開始深さ", "Glue Gap": "接着すき間",
    "Waste Margin": "捨て代", "Female": "雌型", "Male": "雄型",
    "The V-bit's included angle (degrees)": "Vビットの刃先角 (度)",
    "Deepest the V-bit goes; deeper areas cleared flat by the end mill; 0: no limit (mm)":
        "Vビットの最大深さ。これより深い所はエンドミルで平らに削ります。0：制限なし (mm)",
    "The tip's depth where the region is 0 wide (an inlay's plug: how far it goes in) (mm)":
        "領域の幅が0の所での先端の深さ（インレイのプラグ：差し込む深さ） (mm)",
    "How far the path may stray from the medial axis (mm)": "経路が中心軸から外れてよい距離 (mm)",
    "Between the end mill's rings; 0: its radius (mm)": "エンドミルのリングの間隔。0：その半径 (mm)",
    "A plain V-carve, or one half of an inlay": "通常の V 彫り、またはインレイの片側",
    "A plain V-carve": "通常の V 彫り",
    "The inlay's pocket: the design carved in": "インレイのポケット：図柄を彫り込みます",
    "The inlay's plug: the design mirrored, the waste round it carved away":
        "インレイのプラグ：図柄を反転し、周りの捨て部分を彫り取ります",
    "Male: between plug and pocket, square to the walls (mm)": "雄型：プラグとポケットの間、壁に垂直に測る (mm)",
    "Male: board cleared round the plug; 0: twice the widest cut plus 2 mm (mm)":
        "雄型：プラグの周りで削る板の幅。0：最も広い切削の2倍＋2 mm (mm)",
    "Feed down into each path (mm/min)": "各経路へ下る送り (mm/min)",
}
ROUTER_PANEL_TEXTS.update(VCARVE_PANEL_TEXTS)
# text too fine for a V-carve's clearing end mill (toolpath/operations/vcarve/fine.py)
VCARVE_FINE_TEMPLATES = {
    "{}: the clearing's {} mm end mill is too big for {} of {}: {} mm^2 of the flat floor at max depth {} mm is left "
    "to the V-bit's tip (strokes {} mm wide; the end mill needs {} mm)":
        "{0}：除去加工の {1} mm エンドミルは {3} の {2} には太すぎます：最大深さ {5} mm の平らな底のうち {4} mm² が"
        "V ビットの先端に残ります（線幅 {6} mm、エンドミルには {7} mm 必要）",
    "{}; make it at least {} mm tall (now {} mm), or use a smaller end mill or a smaller max depth":
        "{0}。高さを {1} mm 以上にする（現在 {2} mm）か、小さいエンドミルまたは浅い最大深さにしてください",
    "{}; no text up to {} times as tall lets the end mill in: use a smaller end mill or a smaller max depth":
        "{0}。{1} 倍の高さまで大きくしてもエンドミルが入りません。小さいエンドミルまたは浅い最大深さにしてください",
}
NESTED.update({"{}; make it at least {} mm tall (now {} mm), or use a smaller end mill or a smaller max depth": (0,),
               "{}; no text up to {} times as tall lets the end mill in: use a smaller end mill or a smaller max "
               "depth": (0,)})
VCARVE_FINE_TEMPLATES["{}: the {} cannot reach {} part(s) of the flat floor at max depth ({}); the V-bit's tip traces "
                      "them, ridges up to {} mm high may stand there"] = \
    "{0}：{1} は最大深さの平らな底のうち {2} か所（{3}）に届きません。V ビットの先端がなぞり、" \
    "高さ {4} mm までの山が残ることがあります"
MESSAGE_TEMPLATES.update(VCARVE_FINE_TEMPLATES)
MESSAGE_TEMPLATES.update(TOOLLIB_TEMPLATES)
NESTED.update(TOOLLIB_NESTED)
MESSAGE_TEMPLATES.update(WORKLOAD_TEMPLATES)
NESTED.update(WORKLOAD_NESTED)
# merged together (session 12): notes and warnings of the feeds calculator, engraving's too-fine text
# and V-carving that are built in pieces
MERGED_NESTED = {"{}; no text up to {} times as tall lets the tool in: use a smaller tool": (0,),
                 "{} (gaps {} mm wide); make it at least {} mm tall (now {} mm)": (0,),
                 "V-carve {}: clearing the flat floor: {}": (1,)}
MERGED_TEMPLATES = {
    "flutes not given: {} assumed (the charts' router bits)": "刃数の指定なし：{0} 枚刃とみなしました（表のルータービット）",
    "spindle {} rpm for {} m/min capped at the machine's {} rpm":
        "{1} m/min に要る主軸 {0} rpm を機械の {2} rpm に制限しました",
    "spindle raised to the machine's slowest, {} rpm": "主軸を機械の最低回転数 {0} rpm に上げました",
    "feed {} mm/min capped at the machine's {} mm/min: chip load per tooth {} mm":
        "送り {0} mm/min を機械の {1} mm/min に制限しました：1刃送り {2} mm",
    "feed {} mm/min capped at the machine's {} mm/min: feed per revolution {} mm":
        "送り {0} mm/min を機械の {1} mm/min に制限しました：1回転送り {2} mm",
    "the band finishing's {} mm tool is too big for {} of letters {}: {} mm^2 between its strokes is left uncut":
        "帯仕上げの {0} mm 工具は文字 {2} の {1} には太すぎます：線の間の {3} mm² が削り残ります",
    "{}; no text up to {} times as tall lets the tool in: use a smaller tool":
        "{0}。{1} 倍の高さまで大きくしても工具が入りません。小さい工具を使ってください",
    "{} (gaps {} mm wide); make it at least {} mm tall (now {} mm)":
        "{0}（隙間の幅 {1} mm）。高さを {2} mm 以上にしてください（現在 {3} mm）",
    "{}: the {} cannot reach {} part(s) of the flat floor at max depth ({}{}); the V-bit's tip traces them, ridges "
    "up to {} mm high may stand there":
        "{0}：{1} は最大深さの平らな底の {2} か所（{3}{4}）に届きません。V ビットの先端がなぞりますが、"
        "高さ {5} mm までの山が残ることがあります",
    "V-carve {}: clearing the flat floor: {}": "V 彫り {0}：平らな底の除去：{1}",
    "the design mesh is {} x {} mm, under {} mm across: is it in other units (metres read as mm)?":
        "設計形状のメッシュは {0} x {1} mm で、幅 {2} mm 未満です。単位が違いませんか（メートルを mm として読んでいる）？",
    "the part has no length along Z, the spindle axis (Z {} to {} mm): model it around the Z axis":
        "部品に主軸（Z 軸）方向の長さがありません（Z {0}〜{1} mm）。Z 軸の周りにモデリングしてください",
    "the part lies off the spindle axis: X {} to {} mm, Y {} to {} mm, the axis X0 Y0 outside them; model it around "
    "the Z axis":
        "部品が主軸から外れています：X {0}〜{1} mm、Y {2}〜{3} mm で、軸 X0 Y0 がその外にあります。"
        "Z 軸の周りにモデリングしてください",
}
MESSAGE_TEMPLATES.update(MERGED_TEMPLATES)
NESTED.update(MERGED_NESTED)
# the feeds a job's operations take from the calculator (issue 31): Suggest Feeds, job files with a material
FEEDSUSE_OPERATORS = {"Suggest Feeds": "送り・回転数を提案"}
FEEDSUSE_TEXTS = {
    "Fill the selected operation's spindle speed, feeds and steps from the calculator for the stock's material":
        "選択した加工の主軸回転数・送り・切込みを、素材の材料に合わせて計算機の値で埋めます",
    "Suggest Feeds is for profile, pocket, drilling, chamfer and V-carve operations":
        "送り・回転数の提案は輪郭加工・ポケット・穴あけ・面取り・Vカーブの加工が対象です",
    "Suggest Feeds needs the stock's Material: pick it in Machine & Stock first":
        "送り・回転数の提案には素材の材料が必要です。先に「機械と素材」で材料を選んでください",
}
FEEDSUSE_NESTED = {"{}: feeds: {}": (1,)}
FEEDSUSE_TEMPLATES = {
    "Suggested feeds for {} in {}": "{0} の送り・回転数を {1} 用に提案しました",
    "T{}: {} rpm, feed {} mm/min, chip load {} mm per tooth (band {} - {} mm)":
        "T{0}：{1} rpm、送り {2} mm/min、1刃送り {3} mm（範囲 {4}〜{5} mm）",
    "{}: no tool to suggest feeds for: its diameter is not a positive number":
        "{0}：送りを提案する工具がありません。直径が正の数ではありません",
    "{}: feeds: {}": "{0}：送り：{1}",
}
OPERATOR_LABELS.update(FEEDSUSE_OPERATORS)
OPERATOR_DESCRIPTIONS.update(FEEDSUSE_TEXTS)
MESSAGES.update(FEEDSUSE_TEXTS)
MESSAGE_TEMPLATES.update(FEEDSUSE_TEMPLATES)
NESTED.update(FEEDSUSE_NESTED)
INTERFACE_NAMES["Suggested feeds for {} in {}"] = (1,)
# compilenotice.py: batch's line when a first run compiles the numba kernels
MESSAGES["compiling the numba kernels (first run after an install only, about 2-5 s; later runs load them "
         "from numba's cache)"] = "numbaカーネルをコンパイル中です（インストール後の初回のみ、約2～5秒。以降はnumbaのキャッシュから読み込みます）"
# the status bar's progress texts of the stepped operators (the NC exports, Export Job, Simulate, the Sheet
# and Elbow exports): SteppedOperator shows each through translate_message
PROGRESS_TEXTS = {
    "planning": "経路を計算中", "checking": "シミュレーションで検査中", "writing": "書き出し中",
    "unfolding": "展開中", "punching": "パンチング中", "reading": "読み込み中", "cutting": "切削中",
    "done": "完了", "roughing": "荒加工", "finishing": "仕上げ加工", "steep cleanup": "急斜面の追加仕上げ",
    "walls": "壁の等高線仕上げ", "roughing raster": "荒加工のラスター", "band finishing": "帯仕上げ",
    "fine text": "細かすぎる文字の確認", "burr contour": "バリ取り輪郭", "roughing (gouge texture)": "荒加工（彫刻刀跡）",
    "surface": "曲面の確認", "letters on the surface": "曲面上の文字", "radial layers": "半径方向の層",
    "axial layers": "軸方向の層", "operations": "加工工程", "casting radial rays": "半径方向の光線を投射中",
    "casting axial rays": "軸方向の光線を投射中",
}
PROGRESS_NESTED = {"following the surface: {}": (0,)}
PROGRESS_TEMPLATES = {
    "pocket {}": "ポケット {0}",
    "workingstep #{}": "ワーキングステップ #{0}",
    "following the surface: {}": "曲面に沿わせています：{0}",
    "casting {} rays": "{0} 方向の光線を投射中",
}
MESSAGES.update(PROGRESS_TEXTS)
MESSAGE_TEMPLATES.update(PROGRESS_TEMPLATES)
NESTED.update(PROGRESS_NESTED)
# the feeds calculator's notes (how the band was read, what was capped or given): report.json, the reports
FEEDS_NOTES_TEXTS = {
    "a V-bit cuts with its tip: the chart's smallest row": "V ビットは先端で削るため、表の最小径の行",
    "a V-bit cuts with its tip: the chart's smallest row; recommended: the V-groove chart's":
        "V ビットは先端で削るため、表の最小径の行。推奨値は V 溝の表",
    "spindle speed as given": "主軸回転数は指定どおり",
    "feed as given": "送りは指定どおり",
}
FEEDS_NOTES_TEMPLATES = {
    "below the chart's smallest diameter ({} mm): its band scaled by {} / {}":
        "表の最小径（{0} mm）未満のため、その範囲を {1} / {2} 倍に縮小",
    "interpolated between the chart's {} and {} mm rows": "表の {0} mm と {1} mm の行の間を補間",
}
MESSAGES.update(FEEDS_NOTES_TEXTS)
MESSAGE_TEMPLATES.update(FEEDS_NOTES_TEMPLATES)
# One tool library: the preferences point at it, their old list moves into it (operators/oldtools.py).
TOOLLIB_OPERATORS["Move Old Preference Tools"] = "プリファレンスの旧工具を移動"
ONE_LIBRARY_TEXTS = {
    "Edit it in the 3D Viewport's sidebar: CAM > Tool Library": "3D ビューポートのサイドバー「CAM > 工具ライブラリ」で編集します",
    "Move the tools of the preferences' old tool list into the tool library file":
        "プリファレンスの旧工具一覧の工具を工具ライブラリのファイルに移します",
    "The library tool's number (T word)": "ライブラリ工具の番号（T ワード）",
}
ONE_LIBRARY_TEMPLATES = {
    "The preferences' tool {} is no tool and was not moved: {}; type it in CAM > Tool Library":
        "プリファレンスの工具 {0} は工具として使えないため移しませんでした：{1}。CAM > 工具ライブラリで入力し直してください",
    "The preferences' tool {} was not moved: the tool library has T{} as {}, which was kept":
        "プリファレンスの工具 {0} は移しませんでした：工具ライブラリの T{1} は {2} で、そちらを残しました",
    "T{} '{}': the preferences' list held no V-bit angle; it came in as {}°, check it in CAM > Tool Library":
        "T{0} '{1}'：プリファレンスの一覧に V ビットの角度がなかったため {2}° として取り込みました。"
        "CAM > 工具ライブラリで確認してください",
    "The tools not moved are in {} (import it with Replace Same Numbers, or renumber)":
        "移さなかった工具は {0} にあります（「同じ番号を置き換え」で読み込むか、番号を変えてください）",
    "Moved {} tools ({}) from the add-on preferences into the tool library {}; {} were there already":
        "アドオンのプリファレンスから {0} 本の工具（{1}）を工具ライブラリ {2} に移しました。{3} 本はすでにありました",
}
NESTED["The preferences' tool {} is no tool and was not moved: {}; type it in CAM > Tool Library"] = (1,)
MESSAGES.update(ONE_LIBRARY_TEXTS)
MESSAGE_TEMPLATES.update(ONE_LIBRARY_TEMPLATES)
# The setup sheet (toolpath/pictures/setupsheet.py) in Japanese: its own words, looked up by
# :func:`sheet_text` only (not registered with Blender: the sheet is a file, not the interface).
# Words the interface already has ("Machine", "Tools", "Kind" ...) are taken from there, and the
# gate's findings and the notes are messages of the tables above: nothing is listed twice.
SHEET_TEXTS = {
    "Setup": "段取り", "Operations": "加工工程", "Export gate": "書き出しゲート", "Program": "プログラム",
    "Notes": "注記", "Pictures": "図", "Work offset": "ワーク座標系", "Stock": "素材", "Work zero": "ワーク原点",
    "Total time": "合計時間", "Diameter (mm)": "直径 (mm)", "Corner R (mm)": "コーナー R (mm)",
    "Flute length (mm)": "刃長 (mm)", "Stick-out (mm)": "突き出し (mm)", "Chip load (mm)": "チップロード (mm)",
    "Description": "説明", "Spindle (rpm)": "主軸回転数 (rpm)", "Feed (mm/min)": "送り (mm/min)",
    "Plunge (mm/min)": "突込み送り (mm/min)", "Moves": "移動数", "Time (h:mm:ss)": "時間 (h:mm:ss)",
    "Total": "合計", "File": "ファイル", "Size (bytes)": "サイズ (バイト)", "Lines": "行数",
    "No tools in this job.": "このジョブには工具がありません。",
    "No operations in this report.": "このレポートには加工工程がありません。",
    "No program file.": "プログラムファイルはありません。",
    "Passed: the simulation found nothing that stops the program.":
        "合格：シミュレーションでプログラムを止める問題は見つかりませんでした。",
    "Refused: the program was not written.": "拒否：プログラムは書き出されませんでした。",
    "Written despite findings: the override was given knowingly.":
        "指摘があるまま書き出し：承知のうえで強制書き出しが指定されました。",
    "Not run: the export gate did not check this program.": "未実施：書き出しゲートはこのプログラムを検査していません。",
    "Toolpaths": "工具経路", "Result": "加工結果",
    # operations the planners name (turn-mill's); the job's own names stay as typed
    "radial roughing": "径方向の荒加工", "radial finishing": "径方向の仕上げ加工", "axial roughing": "軸方向の荒加工",
    "axial finishing": "軸方向の仕上げ加工",
    # where the work zero sits (setupsheet.work_zero_text)
    "X0 Y0 at the centre of the stock": "X0 Y0 は素材の中心",
    "X0 Y0 at the front-left corner of the stock": "X0 Y0 は素材の左手前の角",
    "X0 Y0 at the front-right corner of the stock": "X0 Y0 は素材の右手前の角",
    "X0 Y0 at the back-left corner of the stock": "X0 Y0 は素材の左奥の角",
    "X0 Y0 at the back-right corner of the stock": "X0 Y0 は素材の右奥の角",
    "left side": "左端", "middle": "中央", "right side": "右端", "front": "手前", "back": "奥",
    "Z0 on the stock top": "Z0 は素材の上面", "Z0 on the stock bottom": "Z0 は素材の下面",
    "X0 Y0 on the axis of rotation": "X0 Y0 は回転軸上",
    "Z0 on the top end face": "Z0 は上端面", "Z0 on the bottom end": "Z0 は下端",
    "the punch's sheet origin (see the program header)": "パンチの板材原点（プログラムのヘッダーを参照）",
}
SHEET_TEMPLATES = {
    "Setup sheet: {}": "段取りシート：{0}",
    "block {} \u00d7 {} \u00d7 {} mm (X {} \u2026 {}, Y {} \u2026 {}, Z {} \u2026 {})":
        "直方体 {0} \u00d7 {1} \u00d7 {2} mm（X {3} \u2026 {4}、Y {5} \u2026 {6}、Z {7} \u2026 {8}）",
    "{}; its top is a curved surface": "{0}。上面は曲面",
    "round \u00d8{} \u00d7 {} mm, axis along Z (Z {} \u2026 {})": "丸材 \u00d8{0} \u00d7 {1} mm、軸は Z 方向（Z {2} \u2026 {3}）",
    "sheet {} mm": "板材 {0} mm", "sheet {} mm, {} mm thick": "板材 {0} mm、板厚 {1} mm",
    "{}/tooth": "{0}/刃", "{}/rev": "{0}/回転",
    "X0 at the stock's {}, Y0 at its {}": "X0 は素材の{0}、Y0 は{1}",
    "Z0 {}": "Z0 は{0}", "{}; {}": "{0}、{1}",
    "{} mm from the left side": "左端から {0} mm", "{} mm left of the left side": "左端の {0} mm 左",
    "{} mm right of the right side": "右端の {0} mm 右", "{} mm from the front": "手前から {0} mm",
    "{} mm in front of the front": "手前の端の {0} mm 手前", "{} mm behind the back": "奥の端の {0} mm 奥",
    "{} mm from the bottom": "下面から {0} mm", "{} mm below the bottom": "下面の {0} mm 下",
    "{} mm above the top": "上面の {0} mm 上", "{} mm from the bottom end": "下端から {0} mm",
    "{} mm below the bottom end": "下端の {0} mm 下", "{} mm above the top end face": "上端面の {0} mm 上",
}
# a tool's kind (the sheet's Kind column): "drill" the tool, not "drill" the operation (穴あけ)
SHEET_CONTEXTS = {"tool kind": {"ball": "ボールエンドミル", "flat": "フラットエンドミル", "bull": "ブルノーズエンドミル",
                                "drill": "ドリル", "vbit": "V ビット"}}
MESSAGE_TEMPLATES["setup sheet language {}: one of {}"] = "段取りシートの言語 {0}：{1} のいずれかです"
MESSAGE_TEMPLATES["the export wrote {}, not {}"] = "書き出しが {1} ではなく {0} に書き込みました"
MESSAGE_TEMPLATES["job file {}: [setup] language = {} is not one of {}"] = \
    "ジョブファイル {0}：[setup] の language = {1} は {2} のいずれでもありません"
# a file the user gave that cannot be read (textfile.file_problem), named by its option or key
FILE_PROBLEM_TEXTS = {
    "no such file": "ファイルがありません",
    "no such file (a part of the path is a file, not a folder)": "ファイルがありません（パスの途中がフォルダーではなくファイルです）",
    "a symbolic link that leads round in a loop, to no file": "シンボリックリンクが循環していて、ファイルに行き着きません",
    "the path is too long for the file system": "パスがファイルシステムの扱える長さを超えています",
    "not readable (permission denied)": "読み取れません（権限がありません）",
    "not a path (it holds a NUL character)": "パスではありません（NUL 文字を含みます）",
    "a folder, not a file": "ファイルではなくフォルダーです",
    "a file": "ファイル", "a drawing file": "図面ファイル", "a mesh file": "メッシュファイル", "an NC file": "NC ファイル",
    "a CDL file": "CDL ファイル", "an ISO 14649 file": "ISO 14649 ファイル", "a font file": "フォントファイル",
    "a .blend file": ".blend ファイル",
}
FILE_PROBLEM_TEMPLATES = {
    "a folder, not {}": "フォルダーです（{0}ではありません）",
    "not a regular file (a device or a pipe), not {}": "通常のファイルではありません（デバイスかパイプです。{0}ではありません）",
    "cannot be read ({})": "読み取れません（{0}）",
    "{}: no tools in it: nothing to import": "{0}：工具が入っていません。取り込むものはありません",
    "line {} is {} characters long, more than the {} this reader takes (an NC block is a few dozen): is it an NC "
    "program?": "{0} 行目は {1} 文字あり、読める {2} 文字を超えています（NC のブロックは数十文字です）。NC プログラムですか？",
    "job file {}: [setup] machine = {} is not a machine preset; they are {}":
        "ジョブファイル {0}：[setup] machine = {1} は機械プリセットではありません。プリセットは {2} です",
    "{} (and {} more row(s) refused)": "{0}（ほかに {1} 行も拒否されました）",
}
for _english, _japanese in FILE_PROBLEM_TEXTS.items():      # a job file's file = "...": the path it came to
    FILE_PROBLEM_TEMPLATES[_english + " ({})"] = _japanese + "（{0}）"
NESTED["a folder, not {}"] = (0,)
NESTED["--nc {}: {}"] = (1,)
NESTED["not a regular file (a device or a pipe), not {}"] = (0,)
NESTED["{} (and {} more row(s) refused)"] = (0,)
MESSAGES.update(FILE_PROBLEM_TEXTS)
MESSAGE_TEMPLATES.update(FILE_PROBLEM_TEMPLATES)
TRANSLATIONS = _build()
_COMPILED = _compiled_templates()


def interface_language() -> str:
    """The setup sheet's language from the panel: "ja" when Blender shows the interface in Japanese
    (as it shows this add-on's labels), else "en"."""
    probe = next(iter(PANEL_TEXTS))
    return "ja" if bpy.app.translations.pgettext_iface(probe) != probe else "en"


def sheet_text(text: str, *values, context: str = "") -> str:
    """A setup sheet's text in Japanese (the sheet's ``translate``, toolpath/pictures/setupsheet.py):
    a template of the sheet with its values put in, a word of the sheet or of the interface, or a
    message (a finding, a note: fixed or filled into its template); as it is when none has one."""
    if values:
        template = SHEET_TEMPLATES.get(text) or MESSAGE_TEMPLATES.get(text)
        return (template or text).format(*values)
    if context:
        return SHEET_CONTEXTS.get(context, {}).get(text, text)
    return SHEET_TEXTS.get(text) or TRANSLATIONS[LOCALE].get((DEFAULT, text)) or japanese_message(text) or text


def register():
    bpy.app.translations.register(__name__, TRANSLATIONS)


def unregister():
    bpy.app.translations.unregister(__name__)
