//! The window's panels, menus and dialogs: one per file, each drawing from the window's state
//! and returning the actions only the app carries out.

pub mod about;
pub mod compare_view;
pub mod cut_menu;
pub mod cutter_panel;
pub mod export_dialog;
pub mod export_labels;
pub mod file_browser;
pub mod help;
pub mod image_panel;
pub mod key_reference;
pub mod menus;
pub mod metrics_panel;
pub mod models_panel;
pub mod open_browser;
pub mod risk_panel;
pub mod status_bar;
pub mod tools_panel;
pub mod turntable_export;
pub mod variants_panel;
pub mod webpage_export;
