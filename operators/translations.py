"""Japanese (ja_JP) translation of the add-on's interface, through ``bpy.app.translations``.

English stays the source and the default; Blender shows these strings when the interface
language is Japanese and "Translate Interface / Tooltips / New Data" are on.  The words are the
ones a Japanese shop floor uses (ボールエンドミル, ステップオーバー, 切込み深さ, ワーク原点, 展開図,
タレットパンチ, ニブリング, 彫刻刀跡 ...).

Lookup contexts: property names and descriptions, enum items, panel and menu labels, tooltips
and messages use the default context ``"*"``; operator labels (buttons, menus, F3 search) use
``"Operator"``, so every operator label is entered in both.

Messages: Blender translates labels and tooltips by itself, but not what Python reports or
raises.  Fixed (whole-string) messages are here; the code translates them at report time with
``bpy.app.translations.pgettext_rpt(message)`` (poll messages with ``pgettext_tip``).  Messages
built with f-strings (object names, counts, lengths) are not translatable this way and are left
in English.
"""
from __future__ import annotations

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
    "CDL": "CDL",
    "CADKEY CDL (.cdl)": "CADKEY CDL (.cdl)",
    "ISO 14649 STEP-NC (.stp, .p21)": "ISO 14649 STEP-NC (.stp, .p21)",
    "ISO 14649 STEP-NC (.stp)": "ISO 14649 STEP-NC (.stp)",
}

# Operator tooltips (the operator classes' docstrings).
OPERATOR_DESCRIPTIONS = {
    "Cut the stock with the job's toolpaths and check for gouges, rapids through material and moves outside "
    "the machine": "ジョブの工具経路で素材を削り、削り込み・材料内の早送り・機械のストローク外の移動を調べます",
    "Put the 3D cursor on a finding and centre the view on it": "指摘箇所に3Dカーソルを置き、ビューの中心に表示します",
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
    "Sheet Metal": "板金",
    "Pipe Elbow": "エビ管",
    "Tool Library": "工具ライブラリ",
    "Twisted quad corners (mm)": "ねじれ四辺形の頂点 (mm)",
    "Pockets: outline objects marked as pockets, on the stock": "ポケット：素材の上の、ポケットに指定した輪郭オブジェクト",
    "The tool library is empty (Preferences > Add-ons > Kezuri CAM)":
        "工具ライブラリが空です（プリファレンス > アドオン > Kezuri CAM）",
}

# Property names and descriptions, enum items (operators/properties.py, preferences.py and the
# operators' own properties).
PROPERTY_TEXTS = {
    "Colour": "色分け",
    "Light wood at the top, dark at the deepest cut": "上面は明るく、最も深い切削ほど濃く",
    "Each operation's surface in its own colour": "各工程が仕上げた面をそれぞれの色で表示",
    # Simulation
    "Job": "ジョブ",
    "Engraving": "彫刻",
    "The gouge-texture name plate": "彫刻刀跡の表札",
    "The pockets on the rotating table": "回転テーブルのポケット",
    "The imported ISO 14649 workplan": "読み込んだISO 14649ワークプラン",
    "The turn-mill part's radial and axial operations": "複合加工部品の径方向・軸方向の加工工程",
    "Kind": "種類",
    "Location": "位置",
    "Message": "メッセージ",
    "Move": "移動",
    "Cell Size": "セルサイズ",
    "Height-field grid spacing (mm)": "ハイトフィールドの格子間隔（mm）",
    "Engine": "エンジン",
    "Height Field": "ハイトフィールド",
    "Fast Z-map of the exact tool envelope (3-axis and C-X-Z jobs)":
        "工具包絡面を正確に求める高速Zマップ（3軸とC-X-Zのジョブ）",
    "Exact Solid": "厳密ソリッド",
    "manifold3d booleans of the swept tools: exact, slower": "工具の掃引体のmanifold3dブーリアン：正確だが低速",
    # Posts and work offsets
    "Post": "ポストプロセッサ",
    "Controller the NC program is written for": "NCプログラムの出力先の制御装置",
    "Preferences Default": "プリファレンスの既定値",
    "The default post of the extension preferences": "エクステンションのプリファレンスで設定した既定のポストプロセッサ",
    "Fanuc (baked texture)": "FANUC（テクスチャをベイク）",
    "Fanuc machining centre, ISO 6983; texture depths written literally":
        "FANUCのマシニングセンタ（ISO 6983）。刀跡の深さを数値のまま書き出します",
    "Fanuc (controller macro)": "FANUC（制御装置マクロ）",
    "Fanuc Custom Macro B: G66.1 P7023 draws the depths on the controller from clock #3001":
        "FANUCカスタムマクロB：G66.1 P7023 が制御装置上でクロック #3001 を種に深さを乱数で決めます",
    "LinuxCNC": "LinuxCNC",
    "LinuxCNC / rs274ngc router or mill (.ngc)": "LinuxCNC / rs274ngc のルーターまたはフライス盤（.ngc）",
    "GRBL": "GRBL",
    "GRBL 1.1 hobby router: no tool changer, M00 pause at each tool change":
        "GRBL 1.1 のホビー用ルーター：自動工具交換装置なし、工具交換のたびに M00 で一時停止",
    "Fanuc": "FANUC",
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
    # Engrave: band finishing and burr contour
    "Flat Diameter": "フラット径",
    "Band finishing flat end mill diameter (mm)": "帯仕上げ用フラットエンドミルの直径 (mm)",
    "Flat Tool No.": "フラットの工具番号",
    "Band Width": "帯の幅",
    "Width of the flat band cut around every letter (mm)": "各文字の周りに平らに削る帯の幅 (mm)",
    "Band Depth": "帯の深さ",
    "Depth of the band around the letters (mm)": "文字の周りの帯の深さ (mm)",
    "Band Stepover": "帯のステップオーバー",
    "Distance between the band's contour passes (mm)": "帯の輪郭加工パスの間隔 (mm)",
    # Engrave: feeds and heights
    "Ball Spindle": "ボールの主軸回転数",
    "Flat Spindle": "フラットの主軸回転数",
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
    "Show rapid moves as well": "早送りの移動も表示します",
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
    "Thickness": "板厚",
    "Sheet thickness; above 3.2 mm the punching line G79 is used (mm)":
        "板厚。3.2 mm を超えるとパンチングライン G79 を使います (mm)",
    "Nibbling Pitch": "ニブリングピッチ",
    "Distance between punch hits (Q word) (mm)": "パンチの打ち抜き間隔（Qワード） (mm)",
    "Station": "ステーション",
    "Turret station (T word)": "タレットのステーション（Tワード）",
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
    "Wall Stepover": "壁面のステップオーバー",
    "Wall finishing pitch along the wall (mm)": "壁面に沿った壁面仕上げのピッチ (mm)",
    "Table Speed Limit": "テーブル回転数の上限",
    "Fastest the face plate turns (rpm), for feeds and times": "面板の最高回転数 (rpm)。送り速度と加工時間の計算に使います",
    "X Z C words, G93 inverse-time feed": "X Z C ワード、G93 逆時間送り",
    "Fanuc flavour of the same program": "同じプログラムのFANUC版",
    "X Z C words, G93 inverse-time feed (.ngc)": "X Z C ワード、G93 逆時間送り（.ngc）",
    "Fanuc flavour of the same program (.nc)": "同じプログラムのFANUC版（.nc）",
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
    "End Mill Tool No.": "エンドミルの工具番号",
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
    "Ray Sample Spacing": "レイのサンプル間隔",
    "Distance between ray samples on each face (mm)": "各面上のレイのサンプル点の間隔 (mm)",
    "Driven tool speed (rpm)": "回転工具の回転数 (rpm)",
    "Ray Engine": "レイ判定エンジン",
    "Blender BVH": "Blender BVH",
    "Blender's BVHTree": "BlenderのBVHTree",
    "trimesh": "trimesh",
    "trimesh (Embree when bundled), as in batch runs": "trimesh（同梱されていればEmbree）。バッチ実行と同じです",
    "Turn-Mill X-Z-C": "複合加工機 X-Z-C",
    "X (diameter), Z, C words with the machine's C-axis and turret codes":
        "X（直径値）、Z、C ワードと、機械のC軸・タレット用コード",
    "LinuxCNC X-Z-C": "LinuxCNC X-Z-C",
    "X (radius), Z, C words only": "X（半径値）、Z、C ワードのみ",
    "APT CL Data": "APT CLデータ",
    "Cutter location data in part coordinates, for a post-processor":
        "ポストプロセッサ用の、部品座標での工具位置（CL）データ",
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
}

# Fixed messages: poll messages, reports and the errors the operators show (run_reported).
MESSAGES = {
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
    "Corners taken from the selected face": "選択した面から頂点を取得しました",
    "Kezuri preferences are not available": "Kezuriのプリファレンスを利用できません",
    "No such tool in the library": "その工具は工具ライブラリにありません",
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
    # toolpath/engrave.py
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
    # toolpath/rotary.py
    "a cutting move could not be linearised for the rotary table (path through the axis?)":
        "切削の移動を回転テーブル用に直線化できませんでした（経路が回転軸を通っていませんか？）",
    "no pockets to cut": "削るポケットがありません",
    # toolpath/unfold.py
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
    # toolpath/simulate.py
    "nothing to simulate: the program has no moves": "シミュレーションするものがありません：プログラムに移動がありません",
    "design surface has NaN heights": "設計面の高さに NaN があります",
    "simulation cancelled": "シミュレーションを中止しました",
    "simulate needs a Program, an Operation or a list of Operations":
        "シミュレーションには Program、Operation、または Operation のリストが必要です",
    "design must be a function z(x, y), a mesh with vertices and faces, or a number":
        "設計形状は関数 z(x, y)、頂点と面を持つメッシュ、または数値で指定してください",
    # toolpath/turnmill.py
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
    # toolpath/stepnc/workplan.py: notes the STEP-NC operators report as warnings
    "the reduced spindle speeds of DRILLING_TYPE_STRATEGY are not written (one spindle speed per operation)":
        "DRILLING_TYPE_STRATEGY の減速した主軸回転数は書き出しません（主軸回転数は工程ごとに1つです）",
    "the spindle is not stopped at the bottom (not written); the reamer is fed out":
        "穴底での主軸停止は書き出しません。リーマは回転したまま送りで抜きます",
    # post/*.py
    "contour has a non-finite coordinate (NaN or infinity)": "輪郭に有限でない座標（NaN または無限大）があります",
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
}


def _build() -> dict:
    messages: dict = {}
    for table in (PROPERTY_TEXTS, PANEL_TEXTS, OPERATOR_DESCRIPTIONS, MESSAGES):
        for english, japanese in table.items():
            messages[(DEFAULT, english)] = japanese
    for table in (OPERATOR_LABELS, OPERATOR_TEXTS):
        for english, japanese in table.items():
            messages[(OPERATOR, english)] = japanese
            # A panel may share an operator's label ("Pipe Elbow"): the panel's wording wins in "*".
            messages.setdefault((DEFAULT, english), japanese)
    return {LOCALE: messages}


TRANSLATIONS = _build()


def register():
    bpy.app.translations.register(__name__, TRANSLATIONS)


def unregister():
    bpy.app.translations.unregister(__name__)
